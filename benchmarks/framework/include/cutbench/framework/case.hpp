#pragma once
// Case files: one TOML file per paper figure or table, under benchmarks/<paper>/<item>.toml.
// The schema is documented in benchmarks/README.md. Loading validates everything up front
// (unknown keys, units, parameter ranges, reference files) so a bad case fails before any output.
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cutbench/common/model.hpp"

namespace cutbench::framework {

using json = nlohmann::json;

// The memory a single solver run may need, from its footprint estimate (SolverSpec::footprint):
// a case with a larger run is refused at load, with the estimate (bad input, exit 2). Default
// kDefaultMaxRunBytes; `cutbench run/runs --max-memory GIB` overrides it.
constexpr double kDefaultMaxRunBytes = 8.0 * 1024 * 1024 * 1024;
void set_max_run_bytes(double bytes);
double max_run_bytes();

// The papers of the suite: the directories of reference_data/ with an inventory, sorted.
const std::vector<std::string>& paper_ids();
bool is_paper_id(const std::string& id);

// The numerical method a solver name belongs to ("mpm_cutting" -> "mpm", for every method in the
// source tree, built or not), or "" for other names.
std::string solver_method(const std::string& model);


struct SweepSpec {
  std::string param;
  std::vector<double> values;  // SI
};

// One point per row of a reference table: model parameters taken from table columns.
struct RowsSpec {
  std::filesystem::path file;
  std::map<std::string, std::string> params;  // model parameter -> column name
};

struct SeriesSpec {
  std::string name;
  std::string model;   // analytic model or solver name
  bool solver = false; // true when `model` names a registered solver
  std::string pending; // non-empty: declared but not computable yet (the solver is missing)
  Values params;       // SI, after tier overrides
  std::optional<SweepSpec> sweep;
  std::optional<RowsSpec> rows;
  // Further parameters swept together with `sweep` (same length), e.g. E_T alongside h.
  std::map<std::string, std::vector<double>> zip;
  // Parameters taken at run time from an earlier series' output (one value, or one per point),
  // e.g. the simulated rubbing force F_nb feeding the bending model: param -> {series, output}.
  std::map<std::string, std::pair<std::string, std::string>> links;
};

struct CheckSpec {
  std::string key, kind, metric, units, source, known_failure, description;
  std::string finding;           // id of the evidence in benchmarks/<paper>/FINDINGS.md ("F03")
  std::string tolerance_source;  // where the tolerance comes from (required for reproduction/validation)
  json scatter;                  // measured run-to-run scatter of the value (check units), or null
  std::string scatter_source;
  std::vector<std::string> tiers;  // evaluated only in these tiers (empty: every tier)
  json value, reference, tolerance;
};

struct CaseSpec {
  std::filesystem::path file;
  std::string id, paper, item_id, item, title, requirement, claim, solver, status, reason;
  std::vector<std::string> models, tiers, assumptions;
  std::vector<SeriesSpec> series;
  std::vector<CheckSpec> checks;
  json plots = json::array();
  json tables = json::array();
  bool implemented() const { return status == "implemented"; }
  bool in_tier(const std::string& tier) const;
};

// Check kinds. `consistency` checks test our own models against themselves (they hold by
// construction or compare a formula with itself): shown apart, never counted as reproduction or
// validation of a paper.
extern const std::vector<std::string> kCheckKinds;
// Longest known_failure text per tier: one or two sentences; the evidence lives in FINDINGS.md.
constexpr std::size_t kMaxKnownFailureChars = 300;

// The finding ids ("F01", ...) of benchmarks/<paper>/FINDINGS.md: headings "## F01: title".
std::vector<std::string> finding_ids(const std::filesystem::path& root, const std::string& paper);

class ReferenceCache;
// The points of a series: each a full parameter set (SI) for one evaluation or solver run.
std::vector<Values> series_points(const SeriesSpec& s, ReferenceCache& refs);

// The parameters a series varies from point to point: the swept one and those zipped with it, or
// those read from the rows of a table.
std::vector<std::string> varied_params(const SeriesSpec& s);

// Root of the source tree (benchmarks/, reference_data/): $CUTBENCH_ROOT, else the build-time path.
std::filesystem::path source_root();

// Load and validate one case; `tier` selects the tier overrides ("quick" or "full").
CaseSpec load_case(const std::filesystem::path& file, const std::string& tier);

// All case files under benchmarks/<paper>/ (sorted by id).
std::vector<std::filesystem::path> discover_case_files(const std::filesystem::path& root);

// Resolve "nairn2015/fig08" or a path to a case file.
std::filesystem::path resolve_case(const std::string& id_or_path, const std::filesystem::path& root);

// Inventory items of a paper: reference_data/<paper>/inventory (id, kind, number, title).
// The inventory's "# key: value" comment lines carry the paper's citation and doi.
struct InventoryItem {
  std::string id, kind, number, title;
};
struct Inventory {
  std::string paper;
  std::map<std::string, std::string> meta;
  std::vector<InventoryItem> items;
};
Inventory load_inventory(const std::filesystem::path& root, const std::string& paper);

}  // namespace cutbench::framework
