#pragma once
// uGIMP shape functions on a regular grid (Bardenhagen & Kober 2004): the particle characteristic
// function is a square of half-width lp that does not deform (uniform GIMP). With 4 particles per
// cell, lp = dx/4. Each 1D weight has support |r| < dx + lp, so at most 3 nodes per direction.
#include <cmath>

namespace cutbench::mpm {

// 1D uGIMP weight S(r) and derivative dS/dr for node-particle distance r = xp - xi.
inline void ugimp_1d(double r, double dx, double lp, double& s, double& ds) {
  const double a = std::fabs(r);
  const double sgn = r < 0.0 ? -1.0 : 1.0;
  if (a < lp) {
    s = 1.0 - (r * r + lp * lp) / (2.0 * dx * lp);
    ds = -r / (dx * lp);
  } else if (a < dx - lp) {
    s = 1.0 - a / dx;
    ds = -sgn / dx;
  } else if (a < dx + lp) {
    const double q = dx + lp - a;
    s = q * q / (4.0 * dx * lp);
    ds = -sgn * q / (2.0 * dx * lp);
  } else {
    s = 0.0;
    ds = 0.0;
  }
}

// Weights of the 3 nodes i0, i0+1, i0+2 along one axis for a particle at coordinate xp
// (grid origin x0, spacing dx). Returns i0. Nodes outside |r| < dx + lp get weight 0.
inline int ugimp_axis(double xp, double x0, double dx, double lp, double w[3], double dw[3]) {
  const double u = (xp - x0) / dx;
  const int c = static_cast<int>(std::floor(u));
  const double f = u - c;
  const int i0 = f < 0.5 ? c - 1 : c;
  for (int k = 0; k < 3; ++k) {
    const double xi = x0 + (i0 + k) * dx;
    ugimp_1d(xp - xi, dx, lp, w[k], dw[k]);
  }
  return i0;
}

}  // namespace cutbench::mpm
