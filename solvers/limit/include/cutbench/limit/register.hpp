#pragma once
#include "cutbench/common/solver.hpp"

namespace cutbench::limit {
// Registers the limit-analysis runners (idempotent): limit_strip, limit_punch, limit_block,
// limit_cutting.
void register_solvers(SolverRegistry& registry);
}  // namespace cutbench::limit
