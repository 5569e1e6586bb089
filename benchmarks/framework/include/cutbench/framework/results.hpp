#pragma once
// In-memory results of one case run, the check records derived from them, and their output:
// one HDF5 file per case (temp file, then rename) and JSON check records.
#include <filesystem>
#include <string>
#include <vector>

#include "cutbench/common/solver.hpp"
#include "cutbench/framework/case.hpp"

namespace cutbench::framework {

struct SeriesResult {
  std::string name, model;
  bool solver = false;
  Table table;                   // one row per point: swept params, outputs/scalars, applicable
  std::vector<std::string> notes;
  std::vector<RunOutput> runs;   // solver runs, one per point (histories and snapshots)
  std::string error;             // non-empty if the series could not be computed
  std::string pending;           // non-empty: declared, not implemented yet
};

struct CheckRecord {
  std::string case_id, key, kind, metric, units, source, known_failure, description;
  std::string finding, tolerance_source, scatter_source;
  double scatter = 0.0;  // measured run-to-run scatter of the value (check units); 0: none given
  // Why the check cannot change its verdict when its computed data are perturbed (audit.cpp);
  // empty when it can fail.
  std::string audit;
  double value = 0.0, reference = 0.0, lower = 0.0, upper = 0.0, tolerance = 0.0, error = 0.0;
  bool has_value = false, has_reference = false, is_range = false, relative_tol = false;
  std::string status;   // PASS, FAIL, ERROR, INCONCLUSIVE, NOT RUN, NOT IMPLEMENTED
  std::string message;  // why NOT RUN, what failed
};

struct CaseResult {
  std::string case_id, tier, status;  // status: as a check's, the worst of them (case_status)
  std::vector<SeriesResult> series;
  std::vector<CheckRecord> checks;
  double wall_time_s = 0.0;
  // SHA-256 over the sources of the case's solver method (its source identity without the build
  // settings): a paper-resolution record made by other solver sources is stale. Empty: analytic.
  std::string solver_sources;
  int threads = 1;
  std::string date;
};

json check_to_json(const CheckRecord& r);
json case_result_to_json(const CaseSpec& spec, const CaseResult& r);

// Writes <dir>/<paper>/<item>.h5 (+ .xdmf when there are snapshots) via a temporary file and
// rename. Returns the final path.
std::filesystem::path write_hdf5(const CaseSpec& spec, const CaseResult& result,
                                 const std::filesystem::path& out_dir);

// Write text atomically: temp file in the same directory, then rename.
void write_atomic(const std::filesystem::path& path, const std::string& text);

std::string software_version();  // "0.1.0+<sha>"
std::string utc_now_iso();

}  // namespace cutbench::framework
