#include "cutbench/sph/kernel.hpp"

#include <cmath>

#include "cutbench/common/errors.hpp"

namespace cutbench::sph {

namespace {
constexpr double kPi = 3.14159265358979323846;
}

CubicSpline2D::CubicSpline2D(double h)
    : h_(h), inv_h_(1.0 / h), sigma_(10.0 / (7.0 * kPi * h * h)), sigma_inv_h_(sigma_ / h) {
  if (!(h > 0.0) || !std::isfinite(h)) throw InputError("h", "smoothing length must be positive");
}

}  // namespace cutbench::sph
