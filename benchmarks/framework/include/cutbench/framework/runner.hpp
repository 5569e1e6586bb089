#pragma once
#include <functional>
#include <map>
#include <string>

#include "cutbench/common/solver.hpp"
#include "cutbench/framework/case.hpp"
#include "cutbench/framework/reference.hpp"
#include "cutbench/framework/results.hpp"
#include "cutbench/framework/run_cache.hpp"

namespace cutbench::framework {

// Register every analytic model and solver that this build contains (idempotent).
void register_all();

// The sources digest of a solver method ("mpm", "sph", "limit", "efg"): its source identity without
// the build settings (cmake/source_identity.cmake). Empty for a method this build lacks.
std::string solver_sources(const std::string& method);

// Compute the series of a case (analytic models and solver runs) and evaluate its checks.
CaseResult run_case(const CaseSpec& spec, const std::string& tier, const ProgressFn& progress);

// One solver run that a case computes (one per point of a solver series), found without running
// anything: its run-cache key and file name (run_cache.hpp). A series whose parameters are linked
// to another series' outputs cannot be planned: its runs have `linked` set and no key.
struct PlannedRun {
  std::string series;
  std::size_t point = 0;  // 1-based within the series
  std::string solver;
  Values params;           // validated, SI (empty when linked)
  std::string key, file;
  std::string linked;      // "needs series 'x'" when the parameters come from another series
};
std::vector<PlannedRun> planned_runs(const CaseSpec& spec);
// Where a planned run stands in a run store (scan_run_store, by file name): "stored", "checkpoint"
// (an unfinished run that will resume), "to compute", or its `linked` reason. Only files usable by
// this build count.
std::string planned_run_state(const PlannedRun& run, const std::map<std::string, StoredRun>& store);

// One solver run through the run cache (run_cache.hpp) when it is on: read back when stored
// (`*reused` true), else computed — resuming from and writing checkpoints — and stored with a
// provenance note (`*path`: the run file). With the cache off, just the run.
RunOutput solver_run(const SolverSpec& sv, const Values& params, const ProgressFn& progress, bool* reused = nullptr,
                     std::string* path = nullptr);

// Evaluate the checks of a case against computed series.
std::vector<CheckRecord> evaluate_checks(const CaseSpec& spec, const std::vector<SeriesResult>& series,
                                         ReferenceCache& refs);

// A recorded check judged again against the case file as it is now (paper-resolution records, whose
// runs take hours): the recorded value, and a reference that a selector computed from the run's
// data, are kept; kind, texts, tolerance, window and literal or reference-file values come from
// the case file.
CheckRecord rejudge_check(const CaseSpec& spec, const CheckSpec& cs, const json& recorded, ReferenceCache& refs);

// Overall status: NOT IMPLEMENTED; else FAIL if any check failed (documented known failures
// included: they stay visible, they only do not fail the exit code); else PASS if any passed;
// else NOT RUN.
std::string case_status(const CaseSpec& spec, const std::vector<CheckRecord>& checks);

}  // namespace cutbench::framework
