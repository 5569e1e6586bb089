#include "cutbench/common/driver.hpp"

namespace cutbench {

DriveReport drive(SteppedRun& run, const std::string& solver) {
  DriveReport report;
  const CheckpointSpec* ck = active_checkpoint();
  if (ck && read_checkpoint(*ck, [&](BinaryReader& r) { run.load(r); })) report.resumed_from_step = run.steps();
  CheckpointClock clock(ck);
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
