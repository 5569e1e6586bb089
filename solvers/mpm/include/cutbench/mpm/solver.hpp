#pragma once
// Registration of the MPM case runner(s) with the framework.
#include "cutbench/common/solver.hpp"

namespace cutbench::mpm {

// Adds the SolverSpec "mpm_cutting" (idempotent: a second call does nothing).
void register_solvers(SolverRegistry& registry);

// The spec itself (parameters, scalars, run function).
SolverSpec cutting_solver_spec();

}  // namespace cutbench::mpm
