// libFuzzer: stored solver runs (.run) and checkpoints (.ckpt) are read from disk written by other
// processes and machines: a damaged file is refused (false), never a crash or a huge allocation.
#include "cutbench/common/checkpoint.hpp"
#include "cutbench/framework/run_cache.hpp"
#include "fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace cutbench;
  static const auto dir = fuzz::scratch("runs");
  const auto run_file = dir / "toy-0000000000000000.run";
  fuzz::write_file(run_file, data, size);
  fuzz::only_input_errors([&] {
    RunOutput run;
    std::string problem;
    (void)framework::load_run(run_file.string(), "toy|source x|a=1", run, &problem);
    (void)framework::scan_run_store(dir.string());
  });
  const auto ckpt = dir / "toy-0000000000000000.ckpt";
  fuzz::write_file(ckpt, data, size);
  fuzz::only_input_errors([&] {
    const CheckpointSpec spec{ckpt.string(), "toy|source x|a=1", 600.0, false};
    (void)read_checkpoint(spec, [](BinaryReader& r) {
      (void)r.u64();
      (void)r.str();
      (void)r.vec();
    });
  });
  std::error_code ec;
  std::filesystem::remove(ckpt, ec);
  return 0;
}
