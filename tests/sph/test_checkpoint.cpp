// Checkpoint and resume of the cutting runner (cutbench run --run-cache): a run interrupted after
// every checkpoint and resumed each time gives the uninterrupted result bit for bit; a checkpoint
// of another run (key) or a damaged file is ignored.
#include <boost/test/unit_test.hpp>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <vector>

#include "cutbench/common/checkpoint.hpp"
#include "cutbench/sph/runners.hpp"

using namespace cutbench;
using namespace cutbench::sph;

namespace {
CuttingSetup small_cut() {
  CuttingSetup c;
  c.particles_over_height = 9;
  c.length = 0.6e-3;
  c.cut_distance = 0.12e-3;
  c.history_window = c.cut_distance / c.speed / 10.0;
  c.snapshots = 3;
  return c;
}

std::string checkpoint_path(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / "cutbench_sph_checkpoint";
  std::filesystem::create_directories(dir);
  const auto p = dir / name;
  std::filesystem::remove(p);
  return p.string();
}

void require_equal(const CuttingResult& a, const CuttingResult& b) {
  BOOST_TEST(a.steps == b.steps);
  BOOST_TEST(a.fc == b.fc, boost::test_tools::per_element());
  BOOST_TEST(a.ft == b.ft, boost::test_tools::per_element());
  BOOST_TEST(a.t == b.t, boost::test_tools::per_element());
  BOOST_TEST(a.fc_mean == b.fc_mean);
  BOOST_TEST(a.ft_mean == b.ft_mean);
  BOOST_TEST(a.T_max == b.T_max);
  BOOST_TEST(a.rake_temperature == b.rake_temperature);
  BOOST_TEST(a.rake_temperature_avg == b.rake_temperature_avg);
  BOOST_TEST(a.tool_T_max == b.tool_T_max);
  BOOST_TEST(a.plastic_heat == b.plastic_heat);
  BOOST_TEST(a.friction_heat == b.friction_heat);
  BOOST_TEST(a.heat_lost == b.heat_lost);
  BOOST_TEST(a.rake_friction_ratio == b.rake_friction_ratio);
  BOOST_REQUIRE(a.snapshots.size() == b.snapshots.size());
  for (std::size_t k = 0; k < a.snapshots.size(); ++k) {
    BOOST_TEST(a.snapshots[k].time == b.snapshots[k].time);
    BOOST_TEST(a.snapshots[k].x == b.snapshots[k].x, boost::test_tools::per_element());
    BOOST_TEST(a.snapshots[k].fields.at("T") == b.snapshots[k].fields.at("T"), boost::test_tools::per_element());
    BOOST_TEST(a.snapshots[k].fields.at("eps_p") == b.snapshots[k].fields.at("eps_p"), boost::test_tools::per_element());
    BOOST_TEST(a.snapshots[k].fields.at("surface") == b.snapshots[k].fields.at("surface"), boost::test_tools::per_element());
  }
}
}  // namespace

BOOST_AUTO_TEST_SUITE(checkpoint)

BOOST_AUTO_TEST_CASE(interrupted_after_every_checkpoint_equals_uninterrupted) {
  const CuttingSetup c = small_cut();
  const CuttingResult ref = run_cutting(c);
  // interval 0: a checkpoint at every clock check (every 256 steps); stop after each and resume
  const CheckpointSpec spec{checkpoint_path("interrupted.ckpt"), "sph test run", 0.0, true};
  CuttingResult r;
  int interruptions = 0;
  std::size_t last_resume = 0;
  for (;;) {
    CheckpointScope scope(spec);
    try {
      r = run_cutting(c);
      break;
    } catch (const CheckpointStop&) {
      ++interruptions;
    }
    BOOST_REQUIRE(interruptions < 100000);
  }
  last_resume = r.drive.resumed_from_step;
  std::cout << "checkpoint test: " << ref.steps << " steps, " << interruptions << " interruptions, last resume at step "
            << last_resume << ", " << ref.snapshots.size() << " snapshots\n";
  BOOST_TEST(interruptions == static_cast<int>((ref.steps - 1) / 256));
  BOOST_TEST(last_resume == 256u * static_cast<std::size_t>(interruptions));
  require_equal(ref, r);
  remove_checkpoint(spec);
}

BOOST_AUTO_TEST_CASE(checkpoint_of_another_run_or_damaged_is_ignored) {
  const CuttingSetup c = small_cut();
  const std::string path = checkpoint_path("other.ckpt");
  {  // write one checkpoint of run "A", then stop
    CheckpointScope scope(CheckpointSpec{path, "run A", 0.0, true});
    BOOST_CHECK_THROW(run_cutting(c), CheckpointStop);
  }
  BOOST_REQUIRE(std::filesystem::exists(path));
  {  // run "B" does not resume from it
    CheckpointScope scope(CheckpointSpec{path, "run B", 1e9, false});
    const auto r = run_cutting(c);
    BOOST_TEST(r.drive.resumed_from_step == 0u);
  }
  {  // damage one payload byte of run A's file: ignored as well
    std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
    f.seekg(0, std::ios::end);
    const auto size = static_cast<std::streamoff>(f.tellg());
    f.seekp(size - 100);
    char b = 0;
    f.read(&b, 1);
    f.seekp(size - 100);
    b = static_cast<char>(b ^ 0x5a);
    f.write(&b, 1);
  }
  {
    CheckpointScope scope(CheckpointSpec{path, "run A", 1e9, false});
    const auto r = run_cutting(c);
    BOOST_TEST(r.drive.resumed_from_step == 0u);
  }
  std::filesystem::remove(path);
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(checkpoint_io)

// A checkpoint that cannot be written (its directory is a file) leaves the run going, with a note.
BOOST_AUTO_TEST_CASE(unwritable_checkpoint_does_not_stop_the_run) {
  const CuttingSetup c = small_cut();
  const std::string blocker = checkpoint_path("not_a_directory");
  std::ofstream(blocker) << "x";
  CheckpointScope scope(CheckpointSpec{blocker + "/run.ckpt", "run C", 0.0, false});
  const auto r = run_cutting(c);
  BOOST_TEST(r.drive.checkpoints_written == 0);
  BOOST_TEST(!r.drive.checkpoint_error.empty());
  BOOST_TEST(r.steps > 256u);
  std::filesystem::remove(blocker);
}

BOOST_AUTO_TEST_SUITE_END()
