// libFuzzer: the reference CSV reader (metadata header, units in the column names) must refuse any
// file with an InputError, and a table it accepts must answer every cell.
#include "cutbench/framework/reference.hpp"
#include "fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace cutbench;
  static const auto file = fuzz::scratch("ref") / "table.csv";
  fuzz::write_file(file, data, size);
  fuzz::only_input_errors([&] {
    const framework::ReferenceTable t = framework::load_reference(file, "fuzz");
    for (const auto& c : t.columns) {
      for (std::size_t r = 0; r < t.rows; ++r) {
        fuzz::only_input_errors([&] { (void)t.si_value(c.name, r); });  // text or empty cells refuse
      }
    }
  });
  return 0;
}
