#pragma once
// Opt-in store of finished solver runs (`cutbench run --run-cache DIR`): a solver run is keyed by
// the solver name, every validated parameter (17 significant digits) and the source identity of
// the solver method that registered it (cmake/source_identity.cmake: a hash of the method's
// sources, of solvers/common and, where linked, of analytic/, with the compiler, build type and
// flags). So an interrupted full tier resumes where it stopped, cases that need the same run (one
// paper's figures drawn from the same simulation) compute it once, and finished runs stay valid
// for every build of the same solver sources, on any machine (`reports/full_tier/runs/` keeps the
// full-tier runs in the repository); any change to those sources, committed or not, gives new
// keys. A solver without a source identity (a test's toy solver) is keyed by the software version
// and a hash of the running executable instead. The key is stored in the file and compared on
// load (a hash collision only costs a recompute); files are written to a per-process temporary
// name and renamed.
#include <functional>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "cutbench/common/model.hpp"
#include "cutbench/common/solver.hpp"

namespace cutbench::framework {

// Source identity of the method that registered `solver` (64 hex digits), set by register_all();
// empty when unknown. The build settings that entered it (compiler, build type, flags, library
// versions) are kept beside it as text, for the provenance of stored runs.
void set_solver_identity(const std::string& solver, const std::string& identity, const std::string& settings = "");
std::string solver_identity(const std::string& solver);
std::string solver_build_settings(const std::string& solver);
// A hash of the running executable's bytes (the key of solvers without a source identity); empty
// when the executable cannot be read.
const std::string& build_identity();

// Key text and file name (<solver>-<16 hex digits>.run) of one solver run.
std::string run_key(const std::string& solver, const Values& params);
// "|name=value" for every parameter (17 significant digits): the parameter part of run_key.
std::string params_key(const Values& params);
std::string run_file_name(const std::string& solver, const std::string& key);

// Binary round trip of a RunOutput (tables, snapshots, scalars with units, notes). The file ends
// with a checksum and is flushed to the disk before it is renamed into place.
void save_run(const std::string& path, const std::string& key, const RunOutput& run);
// False when the file is absent, unreadable, damaged (checksum, truncation) or stored under
// another key; `problem` (when given) says why for a damaged file ("damaged: ...").
bool load_run(const std::string& path, const std::string& key, RunOutput& run, std::string* problem = nullptr);

// The lock of one run of a shared store (<run>.lock: "pid host"), held while the run is computed
// so that two processes never compute the same run or resume each other's checkpoint. A lock of
// a process that no longer runs on this host is taken over; a live holder is waited for (the
// caller then reads the run it stored). Released on destruction.
class RunLock {
public:
  RunLock(const std::string& run_path, const std::function<void(const std::string&)>& waiting);
  ~RunLock();
  RunLock(const RunLock&) = delete;
  RunLock& operator=(const RunLock&) = delete;
  bool waited() const { return waited_; }  // another process held it first

private:
  std::string path_;
  bool waited_ = false;
};

// Whether a live process holds the lock of the run stored at `run_path` (it is computing the run
// now). A lock of a process of this host that no longer runs does not count; one of another host
// counts (it cannot be checked from here; RunLock waits for it too).
bool run_in_progress(const std::string& run_path);
// Who holds it: "pid P on HOST" while run_in_progress, else "".
std::string run_lock_holder(const std::string& run_path);

// Progress of a run being computed into a store: `<run>.progress` holds lines "UNIX_TIME FRACTION"
// (the solver's own fraction done, 0-1), appended at most every `interval_s` seconds while the run
// computes and removed once it is stored. It is what `cutbench runs` shows as the fraction done of
// a running run (the last line) and of a checkpointed one (the last line written before the
// checkpoint), for every solver, without reading the solver's checkpoint format.
class ProgressLog {
public:
  explicit ProgressLog(std::string run_path, double interval_s = 15.0);
  void note(double fraction);  // cheap when called often (writes only after interval_s)
  void remove();               // the run is stored

private:
  std::string path_;
  double interval_s_;
  double last_ = -1e300;
};
// The fraction done recorded for the run stored at `run_path`: the last line written no later than
// `not_after` (unix seconds; +inf: the last line), or a negative value when there is none.
double run_progress(const std::string& run_path, double not_after);
// The fraction done of a run being computed (`running`: the last line) or of a checkpointed one
// (the last line written before its checkpoint, where a resume starts); negative when unknown.
double run_fraction_done(const std::string& run_path, bool running);

// One file of a run store (a run-cache directory such as reports/full_tier/runs): a finished run
// (`.run`) or the checkpoint of an unfinished one (`.ckpt`), read without running anything.
struct StoredRun {
  std::string file;        // file name in the directory
  std::string kind;        // "run" or "checkpoint"
  std::string key;         // as stored
  std::string solver;      // the key's solver name
  std::string identity;    // the key's source identity (empty: keyed by an executable)
  Values params;           // the key's parameters
  // "current" (keyed by this build's identity of the solver), "stale" (other sources or build
  // settings), "executable-keyed" (made before source identities), "unknown solver", "unreadable",
  // "damaged: <why>" (a checksum mismatch or truncation: never read back)
  std::string state;
  std::string provenance;  // the run's "run stored in the run cache: ..." note (runs only)
  Values scalars;          // the run's scalar results (runs only)
  std::map<std::string, std::string> scalar_units;
};
// Every .run and .ckpt file of `dir`, sorted by name. Throws InputError("runs", ...) when `dir`
// is not a readable directory.
std::vector<StoredRun> scan_run_store(const std::string& dir);

// Directory used by run_case (empty: off). Throws InputError("--run-cache", ...) when the
// directory cannot be created or written, or the executable cannot be read for its identity.
void set_run_cache_dir(const std::string& dir);
const std::string& run_cache_dir();

// Wall time between two checkpoints of a solver run made with the run cache on (solvers that
// support checkpoints write <solver>-<hash>.ckpt next to the run file and resume from it; the file
// is removed once the finished run is stored). Default 600 s; must be > 0.
// Stored runs only: a solver run that the run cache does not hold is not computed; solver_run
// throws RunNotStored and the series that needs it is not evaluated (its checks: NOT RUN). For
// evaluating a shared store that other processes (a cluster job array) fill.
void set_run_cache_stored_only(bool on);
bool run_cache_stored_only();
struct RunNotStored : std::runtime_error {
  using std::runtime_error::runtime_error;
};

void set_checkpoint_interval(double seconds);
double checkpoint_interval();

}  // namespace cutbench::framework
