#pragma once
// Cubic B-spline kernel in 2D (Monaghan & Lattanzio 1985), support 2h.
//
//   W(r, h) = s [1 - 1.5 q^2 + 0.75 q^3]   0 <= q < 1
//           = s 0.25 (2 - q)^3              1 <= q < 2
//           = 0                             q >= 2,      q = r/h,  s = 10 / (7 pi h^2).
//
// grad_i W_ij = dW/dr(r_ij) e_ij with x_ij = x_i - x_j, e_ij = x_ij / r_ij.
#include <Eigen/Core>

namespace cutbench::sph {

using Vec2 = Eigen::Vector2d;
using Mat2 = Eigen::Matrix2d;

class CubicSpline2D {
public:
  explicit CubicSpline2D(double h);

  double h() const { return h_; }
  double inv_h() const { return inv_h_; }
  double sigma() const { return sigma_; }  // 10 / (7 pi h^2)
  double sigma_inv_h() const { return sigma_inv_h_; }
  double support() const { return 2.0 * h_; }
  // The kernel inside its support, q = r/h in [0, 2): both pieces computed and one selected, with
  // no branch, so that the pair loops vectorise. The one place the spline is written.
  static double value_in_support(double q, double sigma) {
    const double t = 2.0 - q;
    const double near = sigma * (1.0 - 1.5 * q * q + 0.75 * q * q * q), far = sigma * 0.25 * t * t * t;
    return q < 1.0 ? near : far;
  }
  static double dwdr_in_support(double q, double sigma_inv_h) {  // dW/dr (<= 0)
    const double t = 2.0 - q;
    const double near = sigma_inv_h * (-3.0 * q + 2.25 * q * q), far = -sigma_inv_h * 0.75 * t * t;
    return q < 1.0 ? near : far;
  }
  double value(double r) const {
    const double q = r * inv_h_;
    return q < 2.0 ? value_in_support(q, sigma_) : 0.0;
  }
  double dwdr(double r) const {  // dW/dr (<= 0)
    const double q = r * inv_h_;
    return q < 2.0 ? dwdr_in_support(q, sigma_inv_h_) : 0.0;
  }
  // grad_i W_ij for x_ij = x_i - x_j at distance r = |x_ij| > 0.
  Vec2 gradient(const Vec2& xij, double r) const { return (dwdr(r) / r) * xij; }

private:
  double h_;
  double inv_h_;
  double sigma_;  // 10 / (7 pi h^2)
  double sigma_inv_h_;
};

}  // namespace cutbench::sph
