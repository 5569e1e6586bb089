#pragma once
// Registration of every analytical model as a named `eval` model (SI units in and out).
#include "cutbench/common/model.hpp"

namespace cutbench::analytic {

// Adds all analytical models to the registry (idempotent).
void register_models(ModelRegistry& registry);

}  // namespace cutbench::analytic
