#pragma once
// Below this particle count a loop runs on one thread: the fork/join cost (large when the two
// cores are shared and OpenMP threads spin) exceeds the work. Results do not depend on it.
#include <cstddef>

namespace cutbench::sph::detail {
constexpr std::size_t kOmpMinParticles = 4096;
}
