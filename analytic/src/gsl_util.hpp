#pragma once
// Internal helpers around GSL: the default error handler (abort) is switched off and every
// failing status is turned into cutbench::NumericalError.
#include <functional>
#include <string>

namespace cutbench::analytic::detail {

void gsl_quiet();

// Root of f in [lo, hi] (f(lo) and f(hi) of opposite sign) with GSL's Brent solver.
double brent_root(const std::function<double(double)>& f, double lo, double hi,
                  const std::string& what, double rel_tol = 1e-13);

// First sign change of f on a geometric grid from lo to hi (ratio `growth`), refined by Brent.
// Returns false when f never changes sign from negative to non-negative.
bool first_root_geometric(const std::function<double(double)>& f, double lo, double hi,
                          double growth, const std::string& what, double& root);

}  // namespace cutbench::analytic::detail
