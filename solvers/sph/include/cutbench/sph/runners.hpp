#pragma once
// Case runners of the SPH solver, registered with the framework as SolverSpecs.
#include "cutbench/common/solver.hpp"

namespace cutbench::sph {

// Registers sph_laplacian (Afrasiabi et al. 2021, Fig. 3), ... Calling it twice adds nothing.
void register_solvers(SolverRegistry& registry);

// Fig. 3: Laplacian of f = x^2 + y^2 on an n x n lattice over [-1, 1]^2, V_j = dx^2, h = h/dx * dx.
struct LaplacianReconstruction {
  std::vector<double> x, y, exact, brookshaw, fmfs;
  double brookshaw_interior_mean = 0.0;     // over particles with |x|,|y| <= 0.8
  double brookshaw_interior_max_abs_error = 0.0;
  double brookshaw_corner = 0.0;            // mean of the four corner particles
  double brookshaw_max_abs_error = 0.0;
  double fmfs_max_abs_error = 0.0;
  double fmfs_irregular = 0.0;              // particles where FMFS fell back (expected 0)
};
LaplacianReconstruction laplacian_reconstruction(std::size_t n, double h_over_dx, double jitter_fraction,
                                                 std::uint64_t seed = 1);

}  // namespace cutbench::sph
