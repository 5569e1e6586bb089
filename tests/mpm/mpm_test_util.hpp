#pragma once
// Helpers shared by the MPM verification tests.
#include "cutbench/mpm/problem.hpp"

namespace cutbench::mpm::testing {

// Fill [x0, x1] x [y0, y1] (multiples of dx/2 apart) with 4 particles per cell.
template <class VelFn>
inline void fill_rect(MpmProblem& pb, double dx, double x0, double x1, double y0, double y1, bool rigid, VelFn vel) {
  const double s = 0.5 * dx;
  const int nx = static_cast<int>(std::lround((x1 - x0) / s));
  const int ny = static_cast<int>(std::lround((y1 - y0) / s));
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const double x = x0 + (i + 0.5) * s, y = y0 + (j + 0.5) * s;
      const Eigen::Vector2d v = vel(x, y);
      pb.add_particle(x, y, s * s, rigid, v.x(), v.y());
    }
  }
}

inline void fill_rect(MpmProblem& pb, double dx, double x0, double x1, double y0, double y1, bool rigid) {
  fill_rect(pb, dx, x0, x1, y0, y1, rigid, [](double, double) { return Eigen::Vector2d(0.0, 0.0); });
}

inline HyperelasticJ2 polyethylene(double E_T = 100e6) {
  HyperelasticJ2 m;
  m.K = 980e6;
  m.G = 376e6;
  m.sigma_y0 = 25e6;
  m.Ep = HyperelasticJ2::plastic_modulus(m.youngs(), E_T);
  m.rho = 1000.0;
  return m;
}

inline HyperelasticJ2 elastic() {
  HyperelasticJ2 m = polyethylene();
  m.sigma_y0 = 1e300;
  return m;
}

}  // namespace cutbench::mpm::testing
