// libFuzzer: the quantity/unit parser ("2 mm", "30 deg") must refuse any text with an InputError.
#include <string>

#include "cutbench/common/units.hpp"
#include "fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace cutbench;
  const std::string text(reinterpret_cast<const char*>(data), size);
  for (const Dim d : {Dim::length, Dim::angle, Dim::stress, Dim::dimensionless, Dim::temperature, Dim::time}) {
    fuzz::only_input_errors([&] { (void)parse_quantity(text, d, "fuzz"); });
  }
  fuzz::only_input_errors([&] { (void)unit_info(text, "fuzz"); });
  return 0;
}
