#pragma once
// Verification problems of the EFG solver with closed-form answers, shared by the tests and the
// registered runners (efg_cantilever, efg_wave, efg_patch).
#include "cutbench/efg/explicit.hpp"
#include "cutbench/efg/static.hpp"

namespace cutbench::efg {

// Timoshenko & Goodier cantilever, plane stress, isotropic: fixed at x = 0 (exact displacements
// imposed on the nodes there), parabolic shear traction of resultant P at x = L, y in [-H/2, H/2].
struct CantileverResult {
  int nodes = 0;
  double h = 0.0;               // nodal spacing
  double tip_exact = 0.0;       // u_y(L, 0)
  double tip = 0.0;             // EFG u_y(L, 0)
  double tip_rel_error = 0.0;
  double l2_rel_error = 0.0;    // displacement, over the Gauss points
  double energy_rel_error = 0.0;  // sqrt of strain-energy norm of the error / of the exact
  double max_fint_residual = 0.0;  // explicit small-strain f_int(u) - f_ext at free nodes, relative
};
CantileverResult timoshenko_cantilever(int nx, int ny, double support_factor, const WeightParams& w,
                                       double L = 48.0, double H = 12.0, double E = 3.0e7,
                                       double nu = 0.3, double P = 1000.0);

}  // namespace cutbench::efg
