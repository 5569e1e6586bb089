#include "gsl_util.hpp"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>

#include <cmath>
#include <memory>

#include "cutbench/common/errors.hpp"

namespace cutbench::analytic::detail {

void gsl_quiet() {
  static const bool done = [] {
    gsl_set_error_handler_off();
    return true;
  }();
  (void)done;
}

namespace {
double trampoline(double x, void* params) {
  const auto* f = static_cast<const std::function<double(double)>*>(params);
  return (*f)(x);
}
}  // namespace

double brent_root(const std::function<double(double)>& f, double lo, double hi,
                  const std::string& what, double rel_tol) {
  gsl_quiet();
  gsl_function F;
  F.function = &trampoline;
  F.params = const_cast<std::function<double(double)>*>(&f);
  std::unique_ptr<gsl_root_fsolver, decltype(&gsl_root_fsolver_free)> s(
      gsl_root_fsolver_alloc(gsl_root_fsolver_brent), &gsl_root_fsolver_free);
  if (!s) throw NumericalError(what + ": cannot allocate GSL root solver");
  int status = gsl_root_fsolver_set(s.get(), &F, lo, hi);
  if (status != GSL_SUCCESS) {
    throw NumericalError(what + ": GSL root bracket rejected (" + gsl_strerror(status) + ")");
  }
  for (int iter = 0; iter < 200; ++iter) {
    status = gsl_root_fsolver_iterate(s.get());
    if (status != GSL_SUCCESS) {
      throw NumericalError(what + ": GSL Brent iteration failed (" + gsl_strerror(status) + ")");
    }
    const double a = gsl_root_fsolver_x_lower(s.get());
    const double b = gsl_root_fsolver_x_upper(s.get());
    status = gsl_root_test_interval(a, b, 0.0, rel_tol);
    if (status == GSL_SUCCESS) return gsl_root_fsolver_root(s.get());
  }
  throw NumericalError(what + ": GSL Brent did not converge in 200 iterations");
}

bool first_root_geometric(const std::function<double(double)>& f, double lo, double hi,
                          double growth, const std::string& what, double& root) {
  double x0 = lo;
  double f0 = f(x0);
  if (!(f0 < 0.0)) return false;
  while (x0 < hi) {
    const double x1 = x0 * growth;
    const double f1 = f(x1);
    if (f1 == 0.0) {
      root = x1;
      return true;
    }
    if (f1 > 0.0) {
      root = brent_root(f, x0, x1, what);
      return true;
    }
    x0 = x1;
    f0 = f1;
  }
  return false;
}

}  // namespace cutbench::analytic::detail
