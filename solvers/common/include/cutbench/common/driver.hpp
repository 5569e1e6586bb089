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
#include <functional>
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
  // Steps between two looks at the checkpoint clock (a step of a time loop is cheap; a step of
  // an outer loop around a solve is not).
  virtual std::size_t checkpoint_check_every() const { return 256; }
  // The whole state of the run: the problem and every observer's accumulators.
  virtual void save(BinaryWriter& w) const = 0;
  virtual void load(BinaryReader& r) = 0;
};

// An outer loop around expensive evaluations (a search or a fixed-point iteration over whole
// solves, each taking seconds to minutes, the loop's own state small) as a SteppedRun. Every
// advance() runs the loop from its start: the evaluations already done are answered from their
// records, one new evaluation is done and recorded, and the pass stops before the next one. The
// checkpoint is the list of records (inputs and outputs of each evaluation), so a loop whose
// evaluations are deterministic resumes bit for bit; a record whose inputs differ from the
// replayed call's is an error, never silently reused.
class ReplayedLoop : public SteppedRun {
public:
  bool done() const override { return done_; }
  void advance() override;
  std::size_t steps() const override { return records_.size(); }
  std::size_t checkpoint_check_every() const override { return 1; }
  void save(BinaryWriter& w) const override;
  void load(BinaryReader& r) override;

protected:
  // The whole loop from its start; it calls evaluate() for each evaluation and keeps its result
  // in members of the derived run (set anew on every pass).
  virtual void run_loop() = 0;
  // The outputs of this pass's next evaluation: from its record (inputs must match), or
  // compute()'s, recorded. The pass stops (run_loop unwinds) before a second new evaluation.
  const std::vector<double>& evaluate(const std::vector<double>& inputs,
                                      const std::function<std::vector<double>()>& compute);
  // Position of the last evaluate() in the pass and whether its outputs came from a record.
  std::size_t evaluation_index() const { return next_ - 1; }
  bool replayed() const { return replayed_; }

private:
  struct Record {
    std::vector<double> inputs, outputs;
  };
  struct Pause {};
  std::vector<Record> records_;
  std::size_t next_ = 0;
  bool computed_ = false, replayed_ = false, done_ = false;
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
