#pragma once
// Shared by the libFuzzer harnesses: inputs go through a file (the readers under test read files),
// and only cutbench's InputError is an acceptable way to refuse one; any other exception (a raw
// library message, a bad_alloc from a size read out of the input) is a finding, so it aborts.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

#include "cutbench/common/errors.hpp"

namespace cutbench::fuzz {

// A scratch directory of this process: <tmp>/cutbench-fuzz-<pid>/<sub>.
inline std::filesystem::path scratch(const std::string& sub) {
  const auto dir = std::filesystem::temp_directory_path() / ("cutbench-fuzz-" + std::to_string(::getpid())) / sub;
  std::filesystem::create_directories(dir);
  return dir;
}

inline void write_file(const std::filesystem::path& p, const std::uint8_t* data, std::size_t size) {
  std::ofstream(p, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data),
                                                            static_cast<std::streamsize>(size));
}

template <class F>
void only_input_errors(F&& f) {
  try {
    f();
  } catch (const InputError&) {
  } catch (const std::exception& e) {
    std::fprintf(stderr, "not an InputError: %s\n", e.what());
    std::abort();
  }
}

}  // namespace cutbench::fuzz
