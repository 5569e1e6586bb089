#pragma once
// SolverSpec factories of the SPH runners (registered by register_solvers()).
#include "cutbench/common/solver.hpp"

namespace cutbench::sph::detail {
SolverSpec laplacian_spec();  // runner_laplacian.cpp
SolverSpec heat_spec();       // runner_heat.cpp
SolverSpec cutting_spec();    // runner_cutting.cpp
SolverSpec cutting_inputs_spec();  // runner_cutting.cpp
}  // namespace cutbench::sph::detail
