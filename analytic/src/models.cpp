#include "cutbench/analytic/models.hpp"

namespace cutbench::analytic {

void register_models(ModelRegistry& registry) {
  if (registry.find("merchant")) return;
  // Models are added here as they land (see analytic/README.md).
}

}  // namespace cutbench::analytic
