// libFuzzer: the case loader (TOML case files) must refuse any input with an InputError naming a
// field, never crash, hang or throw anything else.
#include <cstdlib>

#include "cutbench/framework/case.hpp"
#include "cutbench/framework/runner.hpp"
#include "fuzz_common.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  if (!std::getenv("CUTBENCH_ROOT")) ::setenv("CUTBENCH_ROOT", CUTBENCH_FUZZ_ROOT, 0);
  cutbench::framework::register_all();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace cutbench;
  static const auto file = fuzz::scratch("nairn2015") / "fuzz.toml";
  fuzz::write_file(file, data, size);
  fuzz::only_input_errors([&] {
    framework::load_case(file, "quick");
    framework::load_case(file, "full");
  });
  return 0;
}
