#pragma once
// The time loop of a long solver run, written once: advance one step at a time until the run is
// done, write a checkpoint of the whole run (the problem and everything its observers have
// accumulated) every CheckpointSpec::interval_s of wall time, and resume from the checkpoint of
// the same run key when one exists. A run implements SteppedRun; it never opens a file: the
// driver reads and writes the checkpoint (common/checkpoint.hpp) through save() and load().
//
// Resuming is exact: a run that saves and loads its whole state gives, after a resume, the same
// result as an uninterrupted run with the same thread count, bit for bit (tested per solver).
#include <cstddef>
#include <string>
#include <vector>

#include "cutbench/common/binary_io.hpp"
#include "cutbench/common/checkpoint.hpp"

namespace cutbench {

class SteppedRun {
public:
  virtual ~SteppedRun() = default;
  virtual bool done() const = 0;
  // One step of the problem and of its observers (history windows, snapshot schedule, probes).
  virtual void advance() = 0;
  virtual std::size_t steps() const = 0;
  // The whole state of the run: the problem and every observer's accumulators.
  virtual void save(BinaryWriter& w) const = 0;
  virtual void load(BinaryReader& r) = 0;
};

struct DriveReport {
  std::size_t resumed_from_step = 0;  // > 0: resumed from a checkpoint written at that step
  int checkpoints_written = 0;
  std::string checkpoint_error;       // the last checkpoint that could not be written, and why
};

// Advance `run` until done(), with the checkpoint of this thread's run (active_checkpoint(), set
// by the framework's run cache) when there is one. `solver` names the run in messages.
DriveReport drive(SteppedRun& run, const std::string& solver);

// Notes for a run's output: a resume and a checkpoint that could not be written.
std::vector<std::string> drive_notes(const DriveReport& report, const std::string& solver);

}  // namespace cutbench
