#pragma once
// The public seam of the mpm solver library: its registration with the framework. The build
// generates the list of compiled methods from CMake (benchmarks/framework/CMakeLists.txt), which
// includes this header and calls register_solvers() once per method.
#include "cutbench/common/solver.hpp"

namespace cutbench::mpm {

// Adds the method's SolverSpecs to the registry (idempotent: a second call adds nothing).
void register_solvers(SolverRegistry& registry);

}  // namespace cutbench::mpm
