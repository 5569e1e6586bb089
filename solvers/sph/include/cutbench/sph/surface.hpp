#pragma once
// Free-surface detection of Marrone et al. (2010) as used by Afrasiabi et al. (2021, Sec. 4.2);
// clean statement in EQUATIONS.md D2.
//
//  1. lambda_i = min eig(L_i), L_i = sum_j (x_j - x_i) (x) grad W_ij V_j.
//     lambda_i <= lambda_surface (0.2): free surface;  lambda_i > lambda_interior (0.75): interior.
//  2. Otherwise the scan ("umbrella") test: n_i = nu_i/|nu_i|, nu_i = -L_i^{-1} sum_j grad W_ij V_j,
//     tau_i = n_i rotated by 90 deg, T = x_i + h n_i. i is interior if a neighbour j has
//        |x_ji| >= sqrt(2) h and |x_j - T| < h,   or
//        |x_ji| <  sqrt(2) h and |n_i.(x_j - T)| + |tau_i.(x_j - T)| < h;
//     otherwise it is on the free surface. h is the smoothing length (support 2h), as in Marrone.
#include <vector>

#include "cutbench/sph/operators.hpp"

namespace cutbench::sph {

struct SurfaceOptions {
  double lambda_surface = 0.2;
  double lambda_interior = 0.75;  // the paper's threshold
  bool scan_test = true;          // false: every particle with lambda <= lambda_interior is surface
};

struct SurfaceDetection {
  std::vector<char> surface;   // 1 on the free surface
  std::vector<double> lambda;  // smallest eigenvalue of L_i
  std::vector<Vec2> normal;    // outward unit normal (zero where undefined)
  std::size_t count() const;
};

SurfaceDetection detect_free_surface(const ParticleView& p, const SurfaceOptions& options = {});

}  // namespace cutbench::sph
