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

// Plane wave in a bar along x, all nodes held in y (uniaxial strain): a velocity step v0 at x = 0;
// the arrival of v0/2 at x = L/4 and 3L/4 (mid row) gives the measured speed, to compare with
// sqrt(Qbar11/rho) (= sqrt(C11/rho) of Eq 55 at theta = 0).
struct WaveResult {
  double c_exact = 0.0, c_measured = 0.0, rel_error = 0.0;
  long steps = 0;
  std::vector<double> t, v1, v2;  // velocity histories at the two stations
};
WaveResult bar_wave(const Orthotropic& m, double theta, double L, int nx, int ny, double cfl,
                    Kinematics kin = Kinematics::small_strain, const WeightParams& w = WeightParams{},
                    int update_interval = 1);

// Patch tests on an nx x ny node set of [0,Lx] x [0,Ly] (interior jitter as a fraction of h):
// (a) a homogeneous finite deformation F = I + H imposed on all nodes: max |F_G - F| and the
// max relative PK2 error over the Gauss points (total Lagrangian); (b) static patch test: linear
// displacement on boundary nodes, interior solved, max nodal error / (|H| L).
struct PatchResult {
  double max_F_error = 0.0, max_stress_rel_error = 0.0, static_rel_error = 0.0;
};
PatchResult patch_test(const Orthotropic& m, double theta, int nx, int ny, double jitter, int gauss_per_dir,
                       const WeightParams& w = WeightParams{});

}  // namespace cutbench::efg
