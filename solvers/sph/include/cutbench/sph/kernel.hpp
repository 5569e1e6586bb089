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
  double value(double r) const {
    const double q = r * inv_h_;
    if (q < 1.0) return sigma_ * (1.0 - 1.5 * q * q + 0.75 * q * q * q);
    if (q < 2.0) {
      const double t = 2.0 - q;
      return sigma_ * 0.25 * t * t * t;
    }
    return 0.0;
  }
  double dwdr(double r) const {  // dW/dr (<= 0)
    const double q = r * inv_h_;
    if (q < 1.0) return sigma_inv_h_ * (-3.0 * q + 2.25 * q * q);
    if (q < 2.0) {
      const double t = 2.0 - q;
      return -sigma_inv_h_ * 0.75 * t * t;
    }
    return 0.0;
  }
  // W and dW/dr together (one branch; same values as value() and dwdr()).
  void value_dwdr(double r, double& w, double& dw) const {
    const double q = r * inv_h_;
    if (q < 1.0) {
      w = sigma_ * (1.0 - 1.5 * q * q + 0.75 * q * q * q);
      dw = sigma_inv_h_ * (-3.0 * q + 2.25 * q * q);
    } else if (q < 2.0) {
      const double t = 2.0 - q;
      w = sigma_ * 0.25 * t * t * t;
      dw = -sigma_inv_h_ * 0.75 * t * t;
    } else {
      w = dw = 0.0;
    }
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
