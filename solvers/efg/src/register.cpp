// Case runners of the EFG solver, registered with the framework.
#include "cutbench/common/solver.hpp"

namespace cutbench::efg {

void register_solvers(SolverRegistry& registry) {
  (void)registry;  // runners are added as their slices land
}

}  // namespace cutbench::efg
