#include "cutbench/common/driver.hpp"

#include "cutbench/common/errors.hpp"

namespace cutbench {

DriveReport drive(SteppedRun& run, const std::string& solver) {
  DriveReport report;
  const CheckpointSpec* ck = active_checkpoint();
  if (ck && read_checkpoint(*ck, [&](BinaryReader& r) { run.load(r); })) report.resumed_from_step = run.steps();
  CheckpointClock clock(ck, run.checkpoint_check_every());
  while (!run.done()) {
    run.advance();
    if (!clock.due(run.steps()) || run.done()) continue;
    try {  // a checkpoint that cannot be written must not end the run it is there to protect
      write_checkpoint(*ck, [&](BinaryWriter& w) { run.save(w); });
      ++report.checkpoints_written;
    } catch (const std::exception& e) {
      report.checkpoint_error = e.what();
    }
    clock.written();
    if (ck->stop_after_write) {
      throw CheckpointStop(solver + ": stopped after a checkpoint at step " + std::to_string(run.steps()));
    }
  }
  return report;
}

void ReplayedLoop::advance() {
  next_ = 0;
  computed_ = false;
  try {
    run_loop();
    done_ = true;
  } catch (const Pause&) {
  }
}

const std::vector<double>& ReplayedLoop::evaluate(const std::vector<double>& inputs,
                                                  const std::function<std::vector<double>()>& compute) {
  if (next_ < records_.size()) {
    const Record& r = records_[next_++];
    if (r.inputs != inputs) {
      throw NumericalError("outer loop: evaluation " + std::to_string(next_) +
                           " differs from its record (a checkpoint of other sources or settings)");
    }
    replayed_ = true;
    return r.outputs;
  }
  if (computed_) throw Pause{};
  computed_ = true;
  replayed_ = false;
  ++next_;
  records_.push_back({inputs, compute()});
  return records_.back().outputs;
}

void ReplayedLoop::save(BinaryWriter& w) const {
  w.u64(records_.size());
  for (const auto& r : records_) {
    w.vec(r.inputs);
    w.vec(r.outputs);
  }
}

void ReplayedLoop::load(BinaryReader& r) {
  records_.clear();
  const std::uint64_t n = r.u64();
  for (std::uint64_t k = 0; k < n; ++k) {
    Record rec;
    rec.inputs = r.vec();
    rec.outputs = r.vec();
    records_.push_back(std::move(rec));
  }
  done_ = false;
}

std::vector<std::string> drive_notes(const DriveReport& report, const std::string& solver) {
  std::vector<std::string> notes;
  if (!report.checkpoint_error.empty()) {
    notes.push_back(solver + ": a checkpoint could not be written (" + report.checkpoint_error + "); the run went on");
  }
  if (report.resumed_from_step > 0) {
    notes.push_back(solver + ": resumed from a checkpoint at step " + std::to_string(report.resumed_from_step) +
                    " (the result equals an uninterrupted run with the same thread count)");
  }
  return notes;
}

}  // namespace cutbench
