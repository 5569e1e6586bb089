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

// The constants of one grid axis for ugimp_axis: reciprocals taken once, so that a particle's
// weights cost multiplications only (the time loop evaluates them for every particle and step).
struct UgimpGrid {
  double x0 = 0.0, inv_dx = 1.0, l = 0.25;  // origin, 1/dx, lp/dx
  double inv_2l = 2.0, inv_4l = 1.0, inv_l = 4.0;
  UgimpGrid() = default;
  UgimpGrid(double x0_, double dx, double lp)
      : x0(x0_), inv_dx(1.0 / dx), l(lp / dx), inv_2l(0.5 * dx / lp), inv_4l(0.25 * dx / lp), inv_l(dx / lp) {}
};

// Weights of the 3 nodes i0, i0+1, i0+2 along one axis for a particle at coordinate xp. Returns
// i0. Nodes outside |r| < dx + lp get weight 0. The same function as ugimp_1d, written in cell
// units rho = r/dx (S(rho) and dS/dr = dS/drho / dx). A coordinate that is not finite or lies
// further than kFarCells cells from the origin returns -1 (off the grid) with zero weights, so that
// no out-of-range value is converted to int.
inline int ugimp_axis(double xp, const UgimpGrid& g, double w[3], double dw[3]) {
  constexpr double kFarCells = 1e9;
  const double u = (xp - g.x0) * g.inv_dx;
  if (!(u > -kFarCells && u < kFarCells)) {  // also false for NaN
    for (int k = 0; k < 3; ++k) w[k] = dw[k] = 0.0;
    return -1;
  }
  const double c = std::floor(u);
  const int i0 = static_cast<int>(c) - (u - c < 0.5 ? 1 : 0);
  for (int k = 0; k < 3; ++k) {
    const double rho = u - static_cast<double>(i0 + k);
    const double a = std::fabs(rho);
    const double sgn = rho < 0.0 ? -1.0 : 1.0;
    if (a < g.l) {
      w[k] = 1.0 - (rho * rho + g.l * g.l) * g.inv_2l;
      dw[k] = -rho * g.inv_l * g.inv_dx;
    } else if (a < 1.0 - g.l) {
      w[k] = 1.0 - a;
      dw[k] = -sgn * g.inv_dx;
    } else if (a < 1.0 + g.l) {
      const double q = 1.0 + g.l - a;
      w[k] = q * q * g.inv_4l;
      dw[k] = -sgn * q * g.inv_2l * g.inv_dx;
    } else {
      w[k] = 0.0;
      dw[k] = 0.0;
    }
  }
  return i0;
}

// The same with the grid constants given directly (tests, one-off points).
inline int ugimp_axis(double xp, double x0, double dx, double lp, double w[3], double dw[3]) {
  return ugimp_axis(xp, UgimpGrid(x0, dx, lp), w, dw);
}

}  // namespace cutbench::mpm
