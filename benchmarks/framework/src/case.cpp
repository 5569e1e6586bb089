#include "cutbench/framework/case.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>

#include <toml++/toml.h>

#include "cutbench/common/errors.hpp"
#include "cutbench/common/solver.hpp"
#include "cutbench/common/glossary.hpp"
#include "cutbench/framework/methods.hpp"
#include "cutbench/framework/reference.hpp"

namespace cutbench::framework {

const std::vector<std::string> kCheckKinds = {"verification", "reproduction", "validation", "consistency"};

namespace fs = std::filesystem;

namespace {
double g_max_run_bytes = kDefaultMaxRunBytes;
}  // namespace
void set_max_run_bytes(double bytes) { g_max_run_bytes = bytes; }
double max_run_bytes() { return g_max_run_bytes; }

const std::vector<std::string>& paper_ids() {
  // a paper is a directory of reference_data/ with an inventory of its figures and tables; its
  // cases live in benchmarks/<paper>/ (adding a paper needs no C++ edit)
  static const std::vector<std::string> ids = [] {
    std::vector<std::string> out;
    const fs::path dir = source_root() / "reference_data";
    if (fs::is_directory(dir)) {
      for (const auto& e : fs::directory_iterator(dir)) {
        if (e.is_directory() && fs::is_regular_file(e.path() / "inventory")) out.push_back(e.path().filename().string());
      }
    }
    std::sort(out.begin(), out.end());
    return out;
  }();
  return ids;
}

bool is_paper_id(const std::string& id) {
  const auto& ids = paper_ids();
  return std::find(ids.begin(), ids.end(), id) != ids.end();
}

namespace {

const std::set<std::string> kCaseKeys = {
    "id",     "paper",  "item",   "title",       "requirement", "status", "reason",
    "solver", "models", "tiers",  "assumptions", "params",      "tier",   "series",
    "checks", "plots",  "tables", "claim"};
const std::set<std::string> kSeriesKeys = {"name", "model", "params", "sweep", "rows", "zip", "tier", "tiers", "pending", "link"};
const std::set<std::string> kCheckKeys = {"key",    "kind",      "metric",        "value",
                                          "reference", "tolerance", "units",      "source",
                                          "known_failure", "description", "tiers", "finding",
                                          "tolerance_source", "scatter", "scatter_source"};
const std::set<std::string> kKinds(kCheckKinds.begin(), kCheckKinds.end());
const std::set<std::string> kMetrics = {"relative", "absolute", "within", "curve_max_norm",
                                        "windowed_mean", "feature"};
const std::set<std::string> kStatuses = {"implemented", "not_implemented"};
const std::set<std::string> kTiers = {"quick", "full"};

json toml_to_json(const toml::table& t) {
  std::ostringstream os;
  os << toml::json_formatter{t};
  return json::parse(os.str());
}

void check_keys(const json& obj, const std::set<std::string>& allowed, const std::string& where) {
  if (!obj.is_object()) throw InputError(where, "expected a table");
  for (const auto& [k, v] : obj.items()) {
    if (!allowed.count(k)) {
      std::string list;
      for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
      throw InputError(where.empty() ? k : where + "." + k, "unknown key (allowed: " + list + ")");
    }
  }
}

std::string get_string(const json& obj, const std::string& key, const std::string& where,
                       bool required = true) {
  if (!obj.contains(key)) {
    if (required) throw InputError(where + key, "missing required key");
    return {};
  }
  if (!obj[key].is_string()) throw InputError(where + key, "expected a string");
  return obj[key].get<std::string>();
}

// A check's documented failure: a table { quick = "...", full = "..." } whose tiers without a text
// expect the check to pass. A plain string is refused: a text written for the reduced-resolution
// tier must not excuse a failure at the paper's resolution.
std::string known_failure_for_tier(const json& check, const std::string& tier, const std::string& where) {
  if (!check.contains("known_failure")) return {};
  const json& kf = check["known_failure"];
  if (!kf.is_object() || kf.empty()) {
    throw InputError(where + "known_failure",
                     "expected a table of tiers { quick = \"...\", full = \"...\" } naming the tier(s) that fail");
  }
  std::string text;
  for (const auto& [t, v] : kf.items()) {
    if (!kTiers.count(t)) throw InputError(where + "known_failure." + t, "unknown tier '" + t + "' (expected quick or full)");
    if (!v.is_string() || v.get<std::string>().empty()) throw InputError(where + "known_failure." + t, "expected a non-empty string");
    if (v.get<std::string>().size() > kMaxKnownFailureChars) {
      throw InputError(where + "known_failure." + t,
                       "at most " + std::to_string(kMaxKnownFailureChars) + " characters (" +
                           std::to_string(v.get<std::string>().size()) +
                           " given): one or two sentences; the evidence goes to FINDINGS.md under the check's finding");
    }
    if (t == tier) text = v.get<std::string>();
  }
  return text;
}

// Limits checked before a case file is parsed, so that a hostile file cannot exhaust the machine
// (the TOML parser's cost grows with the square of a dotted key's depth).
constexpr std::uintmax_t kMaxCaseFileBytes = 1 << 20;  // the largest case file is about 40 kB
constexpr int kMaxKeyDepth = 8;                         // case files use at most 4 levels

void require_parsable_size(const fs::path& file) {
  std::error_code ec;
  const auto bytes = fs::file_size(file, ec);
  if (!ec && bytes > kMaxCaseFileBytes) {
    throw InputError("case file", file.string() + ": " + std::to_string(bytes) + " bytes (at most " +
                                      std::to_string(kMaxCaseFileBytes) + ")");
  }
  std::ifstream in(file);
  std::string line;
  int lineno = 0, nesting = 0;  // open { and [ of inline tables and arrays, across lines
  while (std::getline(in, line)) {
    ++lineno;
    bool in_string = false;
    const auto first_char = line.find_first_not_of(" \t");
    const bool header = first_char != std::string::npos && line[first_char] == '[' && nesting == 0;
    for (std::size_t k = header ? line.size() : 0; k < line.size(); ++k) {
      const char ch = line[k];
      if (ch == '"' && (k == 0 || line[k - 1] != '\\')) in_string = !in_string;
      if (in_string) continue;
      if (ch == '#') break;
      if (ch == '{' || ch == '[') ++nesting;
      if (ch == '}' || ch == ']') --nesting;
      if (nesting > 2 * kMaxKeyDepth) {
        throw InputError("case file", file.string() + ":" + std::to_string(lineno) + ": values nested more than " +
                                          std::to_string(2 * kMaxKeyDepth) + " levels deep");
      }
    }
    // the key part of a line: a table header, or what comes before '=' (quoted keys count too)
    std::size_t end = line.find('=');
    const auto first = line.find_first_not_of(" \t");
    if (first != std::string::npos && line[first] == '[') end = line.find(']', first);
    if (end == std::string::npos) end = line.size();
    int depth = 0;
    bool quoted = false;
    for (std::size_t k = 0; k < end; ++k) {
      if (line[k] == '"') quoted = !quoted;
      if (!quoted && line[k] == '.') ++depth;
      if (line[k] == '#' && !quoted) break;
    }
    if (depth > kMaxKeyDepth) {
      throw InputError("case file", file.string() + ":" + std::to_string(lineno) + ": a key nested " +
                                        std::to_string(depth + 1) + " levels deep (at most " +
                                        std::to_string(kMaxKeyDepth + 1) + ")");
    }
  }
}

// Names that become HDF5 groups, XML attributes and file names: letters, digits and _ . + - only.
void require_name(const std::string& name, const std::string& field) {
  if (name.empty() || name.size() > 64) throw InputError(field, "a name of 1 to 64 characters");
  for (const unsigned char ch : name) {
    if (!(std::isalnum(ch) || ch == '_' || ch == '.' || ch == '+' || ch == '-')) {
      throw InputError(field, "'" + name + "': only letters, digits and _ . + - (it names HDF5 groups and files)");
    }
  }
}

// Text shown in reports and stored in HDF5 attributes: no control characters.
void require_text(const std::string& text, const std::string& field) {
  for (const unsigned char ch : text) {
    if (ch < 0x20 && ch != '\n' && ch != '\t') throw InputError(field, "text without control characters");
  }
}

double quantity(const json& v, Dim dim, const std::string& field);

// Largest relative tolerance: a relative error beyond 10 (1000 %) is no comparison.
constexpr double kMaxRelativeTolerance = 10.0;

// A check's tolerance, validated when the case is loaded: a finite number >= 0 (relative: at most
// kMaxRelativeTolerance), a "value unit" string of the check's dimension, or { relative = x } /
// { absolute = "q unit" }.
void validate_tolerance(const json& tol, const std::string& metric, const std::string& units, const std::string& field) {
  const Dim dim = unit_info(units, field).dim;
  auto finite_nonneg = [&](double v, bool relative, const std::string& f) {
    if (!(std::isfinite(v) && v >= 0.0)) throw InputError(f, "a finite number >= 0");
    if (relative && v > kMaxRelativeTolerance) {
      throw InputError(f, "a relative tolerance of at most " + std::to_string(static_cast<int>(kMaxRelativeTolerance)) +
                              " (1000 %)");
    }
  };
  if (tol.is_object()) {
    if (tol.size() != 1 || !(tol.contains("relative") || tol.contains("absolute"))) {
      throw InputError(field, "expected { relative = x } or { absolute = x }");
    }
    if (tol.contains("relative")) {
      if (!tol["relative"].is_number()) throw InputError(field + ".relative", "a number");
      finite_nonneg(tol["relative"].get<double>(), true, field + ".relative");
    } else {
      finite_nonneg(quantity(tol["absolute"], dim, field + ".absolute"), false, field + ".absolute");
    }
    return;
  }
  const bool relative = metric == "relative" || metric == "windowed_mean";
  if (tol.is_number()) {
    finite_nonneg(tol.get<double>(), relative, field);
  } else if (tol.is_string() && !relative) {
    finite_nonneg(std::abs(quantity(tol, dim, field)), false, field);
  } else {
    throw InputError(field, relative ? "a number (a fraction of the reference)"
                                     : "a number in the check's units or a \"value unit\" string");
  }
}

std::vector<std::string> get_strings(const json& obj, const std::string& key, const std::string& where) {
  std::vector<std::string> out;
  if (!obj.contains(key)) return out;
  if (!obj[key].is_array()) throw InputError(where + key, "expected an array of strings");
  for (const auto& v : obj[key]) {
    if (!v.is_string()) throw InputError(where + key, "expected an array of strings");
    out.push_back(v.get<std::string>());
  }
  return out;
}

double quantity(const json& v, Dim dim, const std::string& field) {
  if (v.is_number()) return v.get<double>();
  if (v.is_string()) return parse_quantity(v.get<std::string>(), dim, field);
  throw InputError(field, "expected a number or a \"value unit\" string");
}

// A parameter value as a case file writes it, by the parameter's kind: a number or "value unit"
// string (real, integer), true/false (switch), an option name (option).
double param_quantity(const json& v, const ParamSpec& p, const std::string& field) {
  switch (p.kind) {
    case ParamKind::boolean:
      if (!v.is_boolean()) throw InputError(field, "a switch: true or false (got " + v.dump() + ")");
      return v.get<bool>() ? 1.0 : 0.0;
    case ParamKind::option:
      if (!v.is_string()) throw InputError(field, describe_range(p) + " (got " + v.dump() + ")");
      return option_index(p, v.get<std::string>(), field);
    case ParamKind::integer: {
      const double x = quantity(v, p.dim, field);
      if (!(std::isfinite(x) && x == std::round(x))) {
        throw InputError(field, "a whole number (got " + v.dump() + "); expected " + describe_range(p));
      }
      return x;
    }
    case ParamKind::real: break;
  }
  return quantity(v, p.dim, field);
}

const ParamSpec* find_param(const std::vector<ParamSpec>& params, const std::string& name) {
  for (const auto& p : params) {
    if (p.name == name) return &p;
  }
  return nullptr;
}

// "unknown parameter", with the glossary name when `name` is a retired name of a shared quantity.
std::string unknown_param_message(const std::vector<ParamSpec>& params, const std::string& name,
                                  const std::string& model) {
  const auto& retired = glossary::retired_names();
  const auto it = retired.find(name);
  if (it != retired.end() && find_param(params, it->second)) {
    return "unknown parameter of '" + model + "': the glossary name of this quantity is '" + it->second +
           "' (solvers/common/include/cutbench/common/glossary.hpp)";
  }
  return "unknown parameter of '" + model + "' (see `cutbench describe " + model + "`)";
}

// True when some registered solver belongs to this method ("mpm" -> "mpm_cutting", ...).
bool solver_built(const std::string& method) {
  for (const auto& sv : SolverRegistry::instance().all()) {
    if (sv.name.rfind(method + "_", 0) == 0) return true;
  }
  return false;
}

std::vector<double> linspace(double a, double b, int n) {
  std::vector<double> v(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) v[static_cast<std::size_t>(i)] = n == 1 ? a : a + (b - a) * i / (n - 1);
  return v;
}

}  // namespace

std::string solver_method(const std::string& model) {
  for (const auto& m : detail::source_tree_methods()) {
    if (model.rfind(m + "_", 0) == 0) return m;
  }
  return {};
}

std::vector<Values> series_points(const SeriesSpec& s, ReferenceCache& refs) {
  std::vector<Values> pts;
  if (s.sweep) {
    for (std::size_t i = 0; i < s.sweep->values.size(); ++i) {
      Values p = s.params;
      p[s.sweep->param] = s.sweep->values[i];
      for (const auto& [k, v] : s.zip) p[k] = v[i];
      pts.push_back(p);
    }
  } else if (s.rows) {
    const ReferenceTable& t = refs.get(s.rows->file, "series '" + s.name + "'.rows.file");
    for (std::size_t r = 0; r < t.rows; ++r) {
      Values p = s.params;
      for (const auto& [param, col] : s.rows->params) p[param] = t.si_value(col, r);
      pts.push_back(p);
    }
  } else {
    pts.push_back(s.params);
  }
  return pts;
}

bool CaseSpec::in_tier(const std::string& tier) const {
  return std::find(tiers.begin(), tiers.end(), tier) != tiers.end();
}

fs::path source_root() {
  if (const char* env = std::getenv("CUTBENCH_ROOT"); env && *env) return fs::path(env);
#ifdef CUTBENCH_SOURCE_DIR_FW
  return fs::path(CUTBENCH_SOURCE_DIR_FW);
#else
  return fs::current_path();
#endif
}

std::vector<std::string> finding_ids(const fs::path& root, const std::string& paper) {
  std::vector<std::string> ids;
  std::ifstream in(root / "benchmarks" / paper / "FINDINGS.md");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("## ", 0) != 0) continue;
    const auto colon = line.find(':', 3);
    if (colon != std::string::npos) ids.push_back(line.substr(3, colon - 3));
  }
  return ids;
}

std::vector<std::string> varied_params(const SeriesSpec& s) {
  std::vector<std::string> names;
  if (s.sweep) {
    names.push_back(s.sweep->param);
    for (const auto& [k, v] : s.zip) names.push_back(k);
  } else if (s.rows) {
    for (const auto& [k, v] : s.rows->params) names.push_back(k);
  }
  return names;
}

namespace {
std::string name_list(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

// The columns of a series' result table: the varied parameters, then the model's outputs (and
// `applicable`) or the solver's declared scalars.
std::vector<std::string> series_columns(const SeriesSpec& s) {
  std::vector<std::string> cols = varied_params(s);
  if (s.solver) {
    for (const auto& o : SolverRegistry::instance().find(s.model)->scalars) cols.push_back(o.name);
  } else {
    for (const auto& o : ModelRegistry::instance().get(s.model).outputs) cols.push_back(o.name);
    cols.push_back("applicable");
  }
  return cols;
}

// A selector of computed data (a check's value, a link, a plot line) names only what the series'
// model or solver declares: checked at load, before anything runs. `names` are the series of the
// case in every tier; a series of another tier, or a pending one, is not resolved here.
// `scalar`: the selector of a check that reduces it to one number; only there may it read every run
// (run = "each") or reduce a window to its drift.
void validate_selector(const json& sel, const std::string& field, const std::vector<SeriesSpec>& series,
                       const std::set<std::string>& names, const char* output_key = "output", bool scalar = false) {
  if (sel.is_number()) return;  // a constant inside ratio/difference/product
  if (!sel.is_object()) throw InputError(field, "a selector table { series = ..., output = ... }");
  for (const char* op : {"ratio", "difference", "product"}) {
    if (!sel.contains(op)) continue;
    const json& ab = sel[op];
    if (!ab.is_array() || ab.size() != 2) throw InputError(field + "." + op, "expected [a, b]");
    validate_selector(ab[0], field + "." + op + "[0]", series, names, output_key, scalar);
    validate_selector(ab[1], field + "." + op + "[1]", series, names, output_key, scalar);
    return;
  }
  if (!sel.contains("series") || !sel["series"].is_string()) throw InputError(field + ".series", "the name of a series");
  const std::string name = sel["series"].get<std::string>();
  if (!names.count(name)) throw InputError(field + ".series", "no series '" + name + "' in this case");
  const SeriesSpec* s = nullptr;
  for (const auto& ss : series) {
    if (ss.name == name) s = &ss;
  }
  if (!s || !s->pending.empty()) return;  // another tier's series, or declared only
  auto column_name = [&](const char* key) -> std::string {
    if (!sel.contains(key)) return {};
    if (!sel[key].is_string()) throw InputError(field + "." + key, "the name of an output column");
    return sel[key].get<std::string>();
  };
  const std::string out = column_name(output_key), x = column_name("x");
  if (out.empty()) throw InputError(field + "." + output_key, "missing");
  std::vector<std::string> cols;
  std::string owner;
  // the window and reduction options, checked before anything runs
  const bool each_run = sel.contains("run") && sel["run"] == "each";
  if (each_run && !scalar) {
    throw InputError(field + ".run", "\"each\" only in a check's value or reference reduced to one number");
  }
  if (sel.contains("across_runs")) {
    if (!each_run) throw InputError(field + ".across_runs", "needs run = \"each\"");
    static const std::set<std::string> across = {"max", "min", "max_abs", "mean"};
    if (!sel["across_runs"].is_string() || !across.count(sel["across_runs"].get<std::string>())) {
      throw InputError(field + ".across_runs", "one of max, min, max_abs, mean");
    }
  }
  if (sel.contains("window_fraction")) {
    const json& wf = sel["window_fraction"];
    if (sel.contains("window")) throw InputError(field + ".window_fraction", "give window or window_fraction, not both");
    if (!sel.contains("x")) throw InputError(field + ".window_fraction", "needs x");
    if (!wf.is_array() || wf.size() != 2 || !wf[0].is_number() || !wf[1].is_number() ||
        !(wf[0].get<double>() >= 0.0 && wf[0].get<double>() < wf[1].get<double>() && wf[1].get<double>() <= 1.0)) {
      throw InputError(field + ".window_fraction", "[a, b] with 0 <= a < b <= 1");
    }
  }
  if (sel.contains("reduce") && sel["reduce"] == "drift") {
    if (!scalar) throw InputError(field + ".reduce", "drift only in a check's value or reference");
    if (!sel.contains("window") && !sel.contains("window_fraction")) {
      throw InputError(field + ".reduce", "drift needs x and a window (or window_fraction)");
    }
  }
  if (sel.contains("run")) {
    if (!each_run && (!sel["run"].is_number_integer() || sel["run"].get<long long>() < 0)) {
      throw InputError(field + ".run", "the index of a run of the series (0, 1, ...) or \"each\" (every run)");
    }
    if (!s->solver) throw InputError(field + ".run", "series '" + name + "' evaluates a model: it has no runs");
    const SolverSpec& sv = *SolverRegistry::instance().find(s->model);
    std::vector<std::string> tables;
    for (const auto& t : sv.tables) tables.push_back(t.name);
    const std::string tname = sel.value("table", std::string());
    const TableSpec* t = sv.table(tname);
    if (!t) {
      throw InputError(field + ".table", "'" + tname + "' is not a table of " + sv.name + " (tables: " +
                                             name_list(tables) + "; see `cutbench describe " + sv.name + "`)");
    }
    for (const auto& c : t->columns) cols.push_back(c.name);
    owner = "table '" + tname + "' of " + sv.name;
  } else {
    cols = series_columns(*s);
    owner = "series '" + name + "' (" + s->model + ")";
  }
  std::vector<std::pair<std::string, std::string>> named = {{output_key, out}, {"x", x}};
  if (sel.contains("at") && sel["at"].is_object()) {
    for (const auto& [k, v] : sel["at"].items()) named.emplace_back("at." + k, k);
  }
  for (const auto& [key, col] : named) {
    if (col.empty()) continue;
    if (std::find(cols.begin(), cols.end(), col) == cols.end()) {
      throw InputError(field + "." + key, "'" + col + "' is not an output of " + owner + " (has: " + name_list(cols) +
                                              "; see `cutbench describe " + s->model + "`)");
    }
  }
}

std::set<std::string> all_series_names(const json& doc) {
  std::set<std::string> names;
  if (!doc.contains("series") || !doc["series"].is_array()) return names;
  for (const auto& s : doc["series"]) {
    if (s.is_object() && s.contains("name") && s["name"].is_string()) names.insert(s["name"].get<std::string>());
  }
  return names;
}
}  // namespace

std::vector<fs::path> discover_case_files(const fs::path& root) {
  std::vector<fs::path> files;
  for (const auto& paper : paper_ids()) {
    const fs::path dir = root / "benchmarks" / paper;
    if (!fs::is_directory(dir)) continue;
    for (const auto& e : fs::directory_iterator(dir)) {
      if (e.is_regular_file() && e.path().extension() == ".toml") files.push_back(e.path());
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

fs::path resolve_case(const std::string& id_or_path, const fs::path& root) {
  fs::path p(id_or_path);
  if (p.extension() == ".toml") {
    if (!fs::exists(p)) throw InputError("case", "case file not found: " + id_or_path);
    return p;
  }
  const auto slash = id_or_path.find('/');
  if (slash == std::string::npos) {
    throw InputError("case", "'" + id_or_path + "' is neither a case id like nairn2015/fig08 nor a .toml file");
  }
  const std::string paper = id_or_path.substr(0, slash);
  if (!is_paper_id(paper)) {
    throw InputError("case", "unknown paper '" + paper + "' in '" + id_or_path + "'");
  }
  fs::path file = root / "benchmarks" / (id_or_path + ".toml");
  if (!fs::exists(file)) throw InputError("case", "no case file for '" + id_or_path + "' (" + file.string() + ")");
  return file;
}

Inventory load_inventory(const fs::path& root, const std::string& paper) {
  Inventory inv;
  inv.paper = paper;
  const fs::path file = root / "reference_data" / paper / "inventory";
  std::ifstream in(file);
  if (!in) throw InputError("inventory", "missing inventory file " + file.string());
  std::string line;
  while (std::getline(in, line)) {
    const auto b = line.find_first_not_of(" \t");
    if (b == std::string::npos) continue;
    if (line[b] == '#') {
      const auto colon = line.find(':');
      if (colon != std::string::npos) {
        std::string key = line.substr(b + 1, colon - b - 1);
        key.erase(0, key.find_first_not_of(' '));
        key.erase(key.find_last_not_of(' ') + 1);
        std::string value = line.substr(colon + 1);
        value.erase(0, value.find_first_not_of(' '));
        if (!key.empty() && key.find(' ') == std::string::npos) inv.meta[key] = value;
      }
      continue;
    }
    std::istringstream is(line);
    InventoryItem item;
    is >> item.id >> item.kind >> item.number;
    std::getline(is, item.title);
    item.title.erase(0, item.title.find_first_not_of(" \t"));
    inv.items.push_back(item);
  }
  return inv;
}

CaseSpec load_case(const fs::path& file, const std::string& tier) {
  if (!kTiers.count(tier)) throw InputError("tier", "unknown tier '" + tier + "' (expected quick or full)");
  require_parsable_size(file);
  toml::table tbl;
  try {
    tbl = toml::parse_file(file.string());
  } catch (const toml::parse_error& e) {
    std::ostringstream os;
    os << file.string() << ":" << e.source().begin.line << ": " << e.description();
    throw InputError("case file", os.str());
  }
  const json doc = toml_to_json(tbl);
  check_keys(doc, kCaseKeys, "");

  CaseSpec c;
  c.file = file;
  c.id = get_string(doc, "id", "");
  c.paper = get_string(doc, "paper", "");
  c.item = get_string(doc, "item", "");
  c.title = get_string(doc, "title", "");
  require_text(c.title, "title");
  c.requirement = get_string(doc, "requirement", "");
  c.claim = get_string(doc, "claim", "", false);
  if (c.claim.size() > 200) throw InputError("claim", "one line of at most 200 characters");
  c.status = get_string(doc, "status", "");
  c.reason = get_string(doc, "reason", "", false);
  c.solver = get_string(doc, "solver", "");
  c.models = get_strings(doc, "models", "");
  c.tiers = get_strings(doc, "tiers", "");
  c.assumptions = get_strings(doc, "assumptions", "");

  if (!is_paper_id(c.paper)) {
    throw InputError("paper", "unknown paper '" + c.paper + "'");
  }
  const std::string expected_id = file.parent_path().filename().string() + "/" + file.stem().string();
  if (c.id != expected_id) {
    throw InputError("id", "'" + c.id + "' does not match the file location (expected '" + expected_id + "')");
  }
  if (c.id.rfind(c.paper + "/", 0) != 0) throw InputError("id", "must start with the paper id '" + c.paper + "/'");
  c.item_id = c.id.substr(c.paper.size() + 1);
  if (!kStatuses.count(c.status)) {
    throw InputError("status", "'" + c.status + "' (expected implemented or not_implemented)");
  }
  if (c.status == "not_implemented" && c.reason.empty()) {
    throw InputError("reason", "a not_implemented case must say what is missing");
  }
  if (c.tiers.empty()) throw InputError("tiers", "at least one tier (quick, full)");
  for (const auto& t : c.tiers) {
    if (!kTiers.count(t)) throw InputError("tiers", "unknown tier '" + t + "' (expected quick or full)");
  }

  // Global parameters and tier overrides (raw JSON, resolved per series against the model).
  json global = doc.value("params", json::object());
  if (doc.contains("tier")) {
    const json& tiers = doc["tier"];
    check_keys(tiers, kTiers, "tier");
    if (tiers.contains(tier)) {
      check_keys(tiers[tier], {"params"}, "tier." + tier);
      const json tier_params = tiers[tier].value("params", json::object());
      for (const auto& [k, v] : tier_params.items()) global[k] = v;
    }
  }
  std::set<std::string> used_globals;

  const fs::path root = source_root();
  auto& models = ModelRegistry::instance();
  auto& solvers = SolverRegistry::instance();

  if (doc.contains("series")) {
    if (!doc["series"].is_array()) throw InputError("series", "expected an array of tables [[series]]");
    std::size_t idx = 0;
    for (const auto& s : doc["series"]) {
      const std::string where = "series[" + std::to_string(idx++) + "]";
      check_keys(s, kSeriesKeys, where);
      SeriesSpec ss;
      ss.name = get_string(s, "name", where + ".");
      require_name(ss.name, where + ".name");
      const auto series_tiers = get_strings(s, "tiers", where + ".");
      for (const auto& t : series_tiers) {
        if (!kTiers.count(t)) throw InputError(where + ".tiers", "unknown tier '" + t + "' (expected quick or full)");
      }
      if (!series_tiers.empty() &&
          std::find(series_tiers.begin(), series_tiers.end(), tier) == series_tiers.end()) {
        continue;  // this series belongs to another tier
      }
      for (const auto& prev : c.series) {  // one name per series of a tier (HDF5 groups)
        if (prev.name == ss.name) throw InputError(where + ".name", "duplicate series name '" + ss.name + "'");
      }
      ss.model = get_string(s, "model", where + ".");
      const std::string sw = "series '" + ss.name + "'.";
      ss.pending = get_string(s, "pending", sw, false);
      const std::vector<ParamSpec>* pspecs = nullptr;
      if (const auto* m = models.find(ss.model)) {
        pspecs = &m->params;
      } else if (const auto* sv = solvers.find(ss.model)) {
        pspecs = &sv->params;
        ss.solver = true;
      } else if (c.implemented() && ss.pending.empty() && !solver_method(ss.model).empty() &&
                 !solver_built(solver_method(ss.model))) {
        ss.pending = "the " + solver_method(ss.model) + " solver is not in this build (CUTBENCH_SOLVERS=OFF)";
      } else if (c.implemented() && ss.pending.empty()) {
        throw InputError(sw + "model", "unknown model or solver '" + ss.model + "'");
      }
      if (!ss.pending.empty()) pspecs = nullptr;  // declared only
      json params = s.value("params", json::object());
      if (s.contains("tier")) {
        check_keys(s["tier"], kTiers, sw + "tier");
        if (s["tier"].contains(tier)) {
          for (const auto& [k, v] : s["tier"][tier].items()) params[k] = v;
        }
      }
      if (!pspecs) {  // not implemented: keep the declaration, do not resolve
        c.series.push_back(ss);
        continue;
      }
      for (const auto& [k, v] : global.items()) {
        if (find_param(*pspecs, k) && !params.contains(k)) {
          params[k] = v;
          used_globals.insert(k);
        } else if (find_param(*pspecs, k)) {
          used_globals.insert(k);
        }
      }
      for (const auto& [k, v] : params.items()) {
        const ParamSpec* p = find_param(*pspecs, k);
        if (!p) throw InputError(sw + "params." + k, unknown_param_message(*pspecs, k, ss.model));
        ss.params[k] = param_quantity(v, *p, sw + "params." + k);
      }
      auto sweep_values = [&](const json& sweep, const ParamSpec& p, const std::string& f) {
        std::vector<double> vals;
        if (sweep.contains("values")) {
          if (!sweep["values"].is_array()) throw InputError(f + ".values", "an array of values");
          for (const auto& v : sweep["values"]) vals.push_back(param_quantity(v, p, f + ".values"));
        } else if (sweep.contains("from") && sweep.contains("to") && sweep.contains("n")) {
          if (p.kind == ParamKind::option || p.kind == ParamKind::boolean) {
            throw InputError(f, "'" + p.name + "' is " + describe_range(p) + ": list them in values = [...]");
          }
          const double a = param_quantity(sweep["from"], p, f + ".from");
          const double b = param_quantity(sweep["to"], p, f + ".to");
          if (!sweep["n"].is_number_integer() || sweep["n"].get<long long>() < 1 || sweep["n"].get<long long>() > 100000) {
            throw InputError(f + ".n", "a whole number of points in 1..100000 (got " + sweep["n"].dump() + ")");
          }
          const int n = sweep["n"].get<int>();
          vals = linspace(a, b, n);
        } else {
          throw InputError(f, "give either values = [...] or from, to, n");
        }
        if (vals.empty()) throw InputError(f, "sweep has no points");
        return vals;
      };
      if (s.contains("sweep")) {
        const json& sweep = s["sweep"];
        check_keys(sweep, {"param", "values", "from", "to", "n"}, sw + "sweep");
        SweepSpec sp;
        sp.param = get_string(sweep, "param", sw + "sweep.");
        const ParamSpec* p = find_param(*pspecs, sp.param);
        if (!p) throw InputError(sw + "sweep.param", "'" + sp.param + "': " + unknown_param_message(*pspecs, sp.param, ss.model));
        sp.values = sweep_values(sweep, *p, sw + "sweep");
        ss.sweep = sp;
      }
      if (s.contains("zip")) {
        if (!ss.sweep) throw InputError(sw + "zip", "zip needs a sweep to zip with");
        for (const auto& [k, v] : s["zip"].items()) {
          const ParamSpec* p = find_param(*pspecs, k);
          if (!p) throw InputError(sw + "zip." + k, unknown_param_message(*pspecs, k, ss.model));
          std::vector<double> vals;
          if (!v.is_array()) throw InputError(sw + "zip." + k, "an array of values");
          for (const auto& x : v) vals.push_back(param_quantity(x, *p, sw + "zip." + k));
          if (vals.size() != ss.sweep->values.size()) {
            throw InputError(sw + "zip." + k, "has " + std::to_string(vals.size()) + " values, sweep has " +
                                                  std::to_string(ss.sweep->values.size()));
          }
          ss.zip[k] = vals;
        }
      }
      if (s.contains("rows")) {
        if (ss.sweep) throw InputError(sw + "rows", "use either sweep or rows, not both");
        const json& rows = s["rows"];
        check_keys(rows, {"file", "params"}, sw + "rows");
        RowsSpec rs;
        rs.file = root / "reference_data" / c.paper / get_string(rows, "file", sw + "rows.");
        ReferenceTable t = load_reference(rs.file, sw + "rows.file");
        const json row_params = rows.value("params", json::object());
        for (const auto& [k, v] : row_params.items()) {
          if (!find_param(*pspecs, k)) throw InputError(sw + "rows.params." + k, unknown_param_message(*pspecs, k, ss.model));
          if (!v.is_string()) throw InputError(sw + "rows.params." + k, "the name of a column of the reference table");
          const auto col = v.get<std::string>();
          const auto& column = t.column(col);
          const ParamSpec* p = find_param(*pspecs, k);
          if (p->kind == ParamKind::option || p->kind == ParamKind::boolean) {
            throw InputError(sw + "rows.params." + k, "'" + k + "' is " + describe_range(*p) + ", not a table column");
          }
          if (column.unit.empty()) throw InputError(sw + "rows.params." + k, "column '" + col + "' is text");
          const UnitInfo u = unit_info(column.unit, sw + "rows.params." + k);
          if (!same_dimension(u.dim, p->dim)) {
            throw InputError(sw + "rows.params." + k, "column '" + col + "' is in " + column.unit +
                                                         ", parameter needs a " + dim_name(p->dim));
          }
          rs.params[k] = col;
        }
        ss.rows = rs;
      }
      if (s.contains("link")) {
        for (const auto& [k, v] : s["link"].items()) {
          if (!find_param(*pspecs, k)) throw InputError(sw + "link." + k, unknown_param_message(*pspecs, k, ss.model));
          if (!v.is_object() || !v.contains("series") || !v.contains("output") || !v["series"].is_string() ||
              !v["output"].is_string()) {
            throw InputError(sw + "link." + k, "expected { series = \"name\", output = \"column\" }");
          }
          const std::string from = v["series"].get<std::string>();
          bool earlier = false;
          for (const auto& prev : c.series) earlier = earlier || prev.name == from;
          if (!earlier) throw InputError(sw + "link." + k, "series '" + from + "' must be declared before this one");
          validate_selector(v, sw + "link." + k, c.series, all_series_names(doc));
          ss.links[k] = {from, v["output"].get<std::string>()};
        }
      }
      // Validate every point now (ranges, required parameters): bad input fails before output.
      // Linked parameters are only known at run time: validated then.
      if (ss.links.empty()) {
        ModelSpec check_spec{ss.model, "", "", *pspecs, {}, {}};
        ReferenceCache refs;
        const std::vector<Values> pts = series_points(ss, refs);
        const SolverSpec* sv = ss.solver ? solvers.find(ss.model) : nullptr;
        for (const auto& p : pts) {
          Values valid;
          try {
            valid = validate_params(check_spec, p);
          } catch (const InputError& e) {
            throw InputError(sw + "params." + e.field(), std::string(e.what()).substr(e.field().size() + 2));
          }
          if (sv && sv->footprint) {  // resources: refuse what cannot run on this machine before it starts
            const Footprint f = sv->footprint(valid);
            if (!(f.bytes <= max_run_bytes())) {
              std::ostringstream os;
              os.precision(3);
              os << "a run of about " << f.points << " " << f.what << " needs about " << f.bytes / 1073741824.0
                 << " GiB, more than the limit of " << max_run_bytes() / 1073741824.0
                 << " GiB (cutbench run --max-memory GIB raises it)";
              throw InputError(sw + "params", os.str());
            }
          }
        }
      }
      c.series.push_back(std::move(ss));
    }
  }
  const bool any_pending = std::any_of(c.series.begin(), c.series.end(),
                                       [](const SeriesSpec& ss) { return !ss.pending.empty(); });
  if (c.implemented() && !any_pending) {  // a pending series may be the one taking a parameter
    for (const auto& [k, v] : global.items()) {
      if (!used_globals.count(k)) throw InputError("params." + k, "no series model takes this parameter");
    }
  }

  if (doc.contains("checks")) {
    std::size_t idx = 0;
    std::set<std::string> keys;
    std::vector<std::string> findings;  // read on first use
    const std::set<std::string> series_names = all_series_names(doc);
    for (const auto& ch : doc["checks"]) {
      const std::string where = "checks[" + std::to_string(idx++) + "]";
      check_keys(ch, kCheckKeys, where);
      CheckSpec cs;
      cs.key = get_string(ch, "key", where + ".");
      const std::string cw = "check '" + cs.key + "'.";
      if (!keys.insert(cs.key).second) throw InputError(cw + "key", "duplicate check key");
      cs.kind = get_string(ch, "kind", cw);
      if (!kKinds.count(cs.kind)) {
        throw InputError(cw + "kind", "'" + cs.kind + "' (expected verification, reproduction, validation or consistency)");
      }
      cs.metric = get_string(ch, "metric", cw);
      if (!kMetrics.count(cs.metric)) {
        throw InputError(cw + "metric", "'" + cs.metric + "' (expected relative, absolute, within, curve_max_norm, windowed_mean or feature)");
      }
      cs.units = get_string(ch, "units", cw);
      unit_info(cs.units, cw + "units");
      cs.source = get_string(ch, "source", cw);
      cs.known_failure = known_failure_for_tier(ch, tier, cw);
      cs.finding = get_string(ch, "finding", cw, false);
      if (ch.contains("known_failure") && cs.finding.empty()) {
        throw InputError(cw + "finding", "required with known_failure: the id of its evidence in benchmarks/" + c.paper +
                                             "/FINDINGS.md");
      }
      if (!cs.finding.empty()) {
        if (findings.empty()) findings = finding_ids(source_root(), c.paper);
        if (std::find(findings.begin(), findings.end(), cs.finding) == findings.end()) {
          throw InputError(cw + "finding", "'" + cs.finding + "' is not a finding of benchmarks/" + c.paper +
                                               "/FINDINGS.md (a heading \"## " + cs.finding + ": title\")");
        }
      }
      cs.tolerance_source = get_string(ch, "tolerance_source", cw, false);
      if ((cs.kind == "reproduction" || cs.kind == "validation") && cs.tolerance_source.empty()) {
        throw InputError(cw + "tolerance_source",
                         "required for a " + cs.kind + " check: the paper's words, its stated error, a measured "
                         "convergence or scatter study (finding id), or a judgement with its reason");
      }
      if (ch.contains("scatter")) {
        // one quantity, or a table of tiers { quick = ..., full = ... } (scatter depends on resolution)
        const Dim sdim = unit_info(cs.units, cw + "units").dim;
        const json& sc = ch["scatter"];
        const json per_tier = sc.is_object() ? sc : json::object({{tier, sc}});
        for (const auto& [t, v] : per_tier.items()) {
          const std::string f = cw + "scatter" + (sc.is_object() ? "." + t : std::string());
          if (!kTiers.count(t)) throw InputError(f, "unknown tier '" + t + "' (expected quick or full)");
          const double sv = quantity(v, sdim, f);
          if (!(std::isfinite(sv) && sv > 0)) throw InputError(f, "a finite positive quantity in the check's units");
          if (t == tier) cs.scatter = v;
        }
        cs.scatter_source = get_string(ch, "scatter_source", cw);
      } else if (ch.contains("scatter_source")) {
        throw InputError(cw + "scatter_source", "given without scatter");
      }
      cs.description = get_string(ch, "description", cw, false);
      cs.tiers = get_strings(ch, "tiers", cw);
      for (const auto& t : cs.tiers) {
        if (!kTiers.count(t)) throw InputError(cw + "tiers", "unknown tier '" + t + "' (expected quick or full)");
      }
      if (!cs.tiers.empty() && std::find(cs.tiers.begin(), cs.tiers.end(), tier) == cs.tiers.end()) continue;
      if (!ch.contains("value")) throw InputError(cw + "value", "missing");
      if (!ch.contains("reference")) throw InputError(cw + "reference", "missing");
      cs.value = ch["value"];
      cs.reference = ch["reference"];
      cs.tolerance = ch.value("tolerance", json());
      if (!cs.value.is_object()) {
        throw InputError(cw + "value", "a selector of computed data ({ series = ..., output = ... }), not a literal");
      }
      const bool range = cs.metric == "within" || (cs.reference.is_array() && cs.reference.size() == 2);
      if (!range) {
        if (cs.tolerance.is_null()) throw InputError(cw + "tolerance", "missing");
        validate_tolerance(cs.tolerance, cs.metric, cs.units, cw + "tolerance");
      } else if (!cs.reference.is_array() || cs.reference.size() != 2) {
        throw InputError(cw + "reference", "a range [lo, hi] for metric 'within'");
      }
      // Reference files must exist now (a missing file is bad input, not a NOT RUN).
      if (cs.reference.is_object() && cs.reference.contains("file")) {
        load_reference(root / "reference_data" / c.paper / cs.reference["file"].get<std::string>(), cw + "reference.file");
      }
      const bool scalar = cs.metric != "curve_max_norm";
      validate_selector(cs.value, cw + "value", c.series, series_names, "output", scalar);
      if (cs.reference.is_object() && (cs.reference.contains("series") || cs.reference.contains("ratio") ||
                                       cs.reference.contains("difference") || cs.reference.contains("product"))) {
        validate_selector(cs.reference, cw + "reference", c.series, series_names, "output", scalar);
      }
      c.checks.push_back(std::move(cs));
    }
  }
  if (doc.contains("plots")) {
    c.plots = doc["plots"];
    const std::set<std::string> names = all_series_names(doc);
    std::size_t ip = 0;
    for (const auto& plot : c.plots) {
      const std::string pw = "plots[" + std::to_string(ip++) + "]";
      if (!plot.is_object() || !plot.contains("lines") || !plot["lines"].is_array()) continue;
      std::size_t il = 0;
      for (const auto& line : plot["lines"]) {
        const std::string lw = pw + ".lines[" + std::to_string(il++) + "]";
        if (line.is_object() && line.contains("series") && line.contains("y")) {
          validate_selector(line, lw, c.series, names, "y");
        }
      }
    }
  }
  if (doc.contains("tables")) c.tables = doc["tables"];
  return c;
}

}  // namespace cutbench::framework
