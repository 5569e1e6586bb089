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
  double support() const { return 2.0 * h_; }
  double value(double r) const;
  double dwdr(double r) const;  // dW/dr (<= 0)
  // grad_i W_ij for x_ij = x_i - x_j at distance r = |x_ij| > 0.
  Vec2 gradient(const Vec2& xij, double r) const { return (dwdr(r) / r) * xij; }

private:
  double h_;
  double sigma_;  // 10 / (7 pi h^2)
};

}  // namespace cutbench::sph
