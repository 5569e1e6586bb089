#include "cutbench/sph/kernel.hpp"

#include <cmath>

#include "cutbench/common/errors.hpp"

namespace cutbench::sph {

namespace {
constexpr double kPi = 3.14159265358979323846;
}

CubicSpline2D::CubicSpline2D(double h) : h_(h), sigma_(10.0 / (7.0 * kPi * h * h)) {
  if (!(h > 0.0) || !std::isfinite(h)) throw InputError("h", "smoothing length must be positive");
}

double CubicSpline2D::value(double r) const {
  const double q = r / h_;
  if (q < 1.0) return sigma_ * (1.0 - 1.5 * q * q + 0.75 * q * q * q);
  if (q < 2.0) {
    const double t = 2.0 - q;
    return sigma_ * 0.25 * t * t * t;
  }
  return 0.0;
}

double CubicSpline2D::dwdr(double r) const {
  const double q = r / h_;
  if (q < 1.0) return sigma_ / h_ * (-3.0 * q + 2.25 * q * q);
  if (q < 2.0) {
    const double t = 2.0 - q;
    return -sigma_ / h_ * 0.75 * t * t;
  }
  return 0.0;
}

}  // namespace cutbench::sph
