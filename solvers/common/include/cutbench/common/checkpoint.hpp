#pragma once
// Checkpoints of long solver runs, so that a full-tier run that takes longer than the time a
// machine is available resumes where it stopped instead of starting again.
//
// The caller that knows the identity of a run (the framework's run cache: solver, parameters,
// software version and a hash of the executable) opens a CheckpointScope around the solver call;
// a solver that supports checkpoints asks active_checkpoint() and, when one is set, first tries
// read_checkpoint() (resume) and then writes write_checkpoint() every `interval_s` seconds of wall
// time. A checkpoint file holds a magic, the run key, the payload length and an FNV-1a checksum
// of the payload: a file of another run, a truncated or a corrupt file is ignored (the run starts
// from the beginning). Files are written to a temporary name and renamed. Resuming gives the same
// result as an uninterrupted run with the same thread count, bit for bit (tested per solver).
#include <chrono>
#include <cstddef>
#include <functional>
#include <stdexcept>
#include <string>

#include "cutbench/common/binary_io.hpp"

namespace cutbench {

struct CheckpointSpec {
  std::string path;                // checkpoint file
  std::string key;                 // identity of the run
  double interval_s = 600.0;       // wall time between two checkpoints
  bool stop_after_write = false;   // tests: throw CheckpointStop after the first write
};

// Thrown after a checkpoint was written when CheckpointSpec::stop_after_write is set (tests use it
// to interrupt a run at a known point).
struct CheckpointStop : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The checkpoint of the solver run in progress on this thread (nullptr: none requested).
const CheckpointSpec* active_checkpoint();

class CheckpointScope {
public:
  explicit CheckpointScope(CheckpointSpec spec);
  ~CheckpointScope();
  CheckpointScope(const CheckpointScope&) = delete;
  CheckpointScope& operator=(const CheckpointScope&) = delete;

private:
  CheckpointSpec spec_;
  const CheckpointSpec* previous_;
};

// Write the payload produced by `body` (throws std::runtime_error when the file cannot be written).
void write_checkpoint(const CheckpointSpec& spec, const std::function<void(BinaryWriter&)>& body);
// Read a checkpoint of this run: false when there is none, it belongs to another key, or it is
// truncated or corrupt (checked before `body` sees any of it).
bool read_checkpoint(const CheckpointSpec& spec, const std::function<void(BinaryReader&)>& body);
void remove_checkpoint(const CheckpointSpec& spec);

// When to write: asked every step, looks at the clock every `check_every` steps.
class CheckpointClock {
public:
  explicit CheckpointClock(const CheckpointSpec* spec, std::size_t check_every = 256);
  bool due(std::size_t step);
  void written();

private:
  const CheckpointSpec* spec_;
  std::size_t check_every_;
  std::chrono::steady_clock::time_point last_;
};

}  // namespace cutbench
