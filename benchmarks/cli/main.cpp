// cutbench — the command line: list, run, eval, bench, report, runs, records, audit.
// Exit codes: 0 all pass, 1 a check failed (or an internal error), 2 bad input (nothing written),
// 3 a run faulted (ERROR: a series threw, a non-finite solver output, a blow-up guard).
#include <CLI/CLI.hpp>

#include <cerrno>
#include <chrono>
#include <cctype>
#include <deque>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <set>
#include <sstream>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "cutbench/common/checkpoint.hpp"
#include "cutbench/common/errors.hpp"
#include "cutbench/framework/run_cache.hpp"
#include "cutbench/framework/audit.hpp"
#include "cutbench/framework/case.hpp"
#include "cutbench/framework/runner.hpp"
#include "cutbench/framework/store.hpp"

// after the project headers: <signal.h> (through <sys/wait.h>) defines a macro `si_value`
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>

#include "slurm.hpp"

namespace fs = std::filesystem;
using namespace cutbench;
using namespace cutbench::framework;

namespace {

constexpr int kExitFail = 1;
constexpr int kExitBadInput = 2;
constexpr int kExitError = 3;  // a run faulted: a series threw, a non-finite output, a blow-up guard
constexpr int kExitSkip = 77;  // ctest SKIP_RETURN_CODE for NOT IMPLEMENTED cases

// Parse key=value pairs for a model/solver against its parameter specs.
Values parse_assignments(const std::vector<std::string>& args, const std::vector<ParamSpec>& specs,
                         const std::string& owner) {
  Values v;
  for (const auto& a : args) {
    const auto eq = a.find('=');
    if (eq == std::string::npos || eq == 0) throw InputError(a, "expected key=value");
    const std::string key = a.substr(0, eq);
    const ParamSpec* p = nullptr;
    for (const auto& s : specs) {
      if (s.name == key) p = &s;
    }
    if (!p) {
      std::string known;
      for (const auto& s : specs) known += (known.empty() ? "" : ", ") + s.name;
      throw InputError(key, "unknown parameter of '" + owner + "' (known: " + known + ")");
    }
    if (v.count(key)) throw InputError(key, "given twice");
    v[key] = parse_param_value(*p, a.substr(eq + 1), key);
  }
  return v;
}

std::string fmt(double v, int prec = 6) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  std::ostringstream os;
  os << std::setprecision(prec) << v;
  return os.str();
}

class Progress {
public:
  explicit Progress(bool enabled) : enabled_(enabled), t0_(std::chrono::steady_clock::now()) {}
  void operator()(double f, const std::string& msg) {
    if (!enabled_) return;
    const auto now = std::chrono::steady_clock::now();
    if (now - last_ < std::chrono::seconds(2) && f < 1.0) return;
    last_ = now;
    const double el = std::chrono::duration<double>(now - t0_).count();
    const double eta = f > 1e-6 ? el * (1 - f) / f : 0.0;
    std::fprintf(stderr, "  [%5.1f%%] %s  elapsed %.0fs ETA %.0fs\n", 100 * f, msg.c_str(), el, eta);
  }

private:
  bool enabled_;
  std::chrono::steady_clock::time_point t0_, last_{};
};

// A verdict as one word for the table: "FAIL (known)" when every failing check is documented for
// that tier, and " stale" appended when a record was made by other solver sources than this build's.
std::string verdict_word(const json& v) {
  std::string s = v.value("status", std::string("NOT RUN"));
  if (s == "FAIL" && v.value("unexpected_failures", 1) == 0) s = "FAIL (known)";
  if (v.value("stale", false)) s += " stale";
  return s;
}

int cmd_list(bool as_json, const fs::path& results, const std::string& paper_filter) {
  const fs::path root = source_root();
  json all = json::array();
  std::map<std::string, std::map<std::string, int>> counts;
  for (const auto& file : discover_case_files(root)) {
    CaseSpec c = load_case(file, "quick");
    if (!paper_filter.empty() && c.paper != paper_filter) continue;
    const json v = case_verdicts(results, c);
    const std::string paper_word = verdict_word(v["paper_resolution"]);
    counts[c.paper][paper_word]++;
    json j = {{"case", c.id},          {"paper", c.paper},   {"item", c.item},
              {"title", c.title},      {"solver", c.solver}, {"models", c.models},
              {"tiers", c.tiers},      {"status", paper_word}, {"paper_resolution", v["paper_resolution"]},
              {"regression", v["regression"]}};
    if (!c.claim.empty()) j["claim"] = c.claim;
    if (!c.implemented()) j["reason"] = c.reason;
    all.push_back(j);
  }
  if (as_json) {
    std::cout << all.dump(2) << "\n";
    return 0;
  }
  std::cout << std::left << std::setw(28) << "CASE" << std::setw(10) << "SOLVER" << std::setw(26)
            << "PAPER RESOLUTION" << "REGRESSION (quick tier, reduced resolution)\n";
  for (const auto& j : all) {
    std::cout << std::left << std::setw(28) << j["case"].get<std::string>() << std::setw(10)
              << j["solver"].get<std::string>() << std::setw(26) << j["status"].get<std::string>()
              << verdict_word(j["regression"]) << "\n";
  }
  std::cout << "\nPaper-resolution verdicts (full-tier records; analytic cases: their evaluation):\n";
  for (const auto& [paper, m] : counts) {
    int n = 0;
    for (const auto& [s, k] : m) n += k;
    std::cout << paper << ": " << n << " cases";
    for (const auto& [s, k] : m) std::cout << ", " << k << " " << s;
    std::cout << "\n";
  }
  std::cout << "FAIL (known): every failing check is a documented known failure of that tier (reason and finding\n"
               "in the report); it stays FAIL. stale: the record was made by other solver sources than this build's.\n"
               "NOT YET RUN: no paper-resolution record; the regression column is the reduced-resolution quick tier.\n";
  return 0;
}

// Case files named by id or path, plus every case of `paper` (every case when `all` and no paper).
std::vector<fs::path> select_case_files(const std::vector<std::string>& ids, const std::string& paper, bool all) {
  const fs::path root = source_root();
  std::vector<fs::path> files;
  for (const auto& id : ids) files.push_back(resolve_case(id, root));
  if (!paper.empty() || all) {
    if (!paper.empty() && !is_paper_id(paper)) {
      throw InputError("--paper", "unknown paper '" + paper + "'");
    }
    for (const auto& f : discover_case_files(root)) {
      if (!paper.empty() && f.parent_path().filename() != paper) continue;
      files.push_back(f);
    }
  }
  return files;
}


// Case statuses of one `cutbench run`, counted, and its summary line.
struct CaseTally {
  int pass = 0, fail = 0, error = 0, inconclusive = 0, not_run = 0, not_implemented = 0;
  void add(const std::string& s) {
    (s == "PASS" ? pass : s == "FAIL" ? fail : s == "ERROR" ? error : s == "INCONCLUSIVE" ? inconclusive
     : s == "NOT RUN" ? not_run : not_implemented)++;
  }
  void print(std::size_t cases, const std::string& tier_label, const fs::path& out) const {
    std::cout << "\n" << cases << " cases (" << tier_label << "): " << pass << " PASS, " << fail << " FAIL, " << error
              << " ERROR, " << inconclusive << " INCONCLUSIVE, " << not_run << " NOT RUN, " << not_implemented
              << " NOT IMPLEMENTED; results in " << out.string() << "\n";
  }
};

// The cases of one `cutbench run` on `jobs` worker processes, each a `cutbench run` of one case
// into the same results directory (its console lines printed when it ends); the summary and the
// exit code as one process would give them.
int run_cases_in_parallel(const std::vector<fs::path>& files, const std::vector<CaseSpec>& cases, const std::string& tier,
                          const fs::path& out, bool strict, int jobs, const std::vector<std::string>& pass_through) {
  const std::string self = fs::read_symlink("/proc/self/exe").string();
  fs::create_directories(out);
  struct Worker {
    pid_t pid;
    std::size_t index;
    fs::path log;
  };
  std::vector<Worker> running;
  int n_error_exit = 0, n_fail_exit = 0;
  std::size_t next = 0;
  auto finish_one = [&]() {
    int status = 0;
    pid_t pid = -1;
    while ((pid = ::waitpid(-1, &status, 0)) < 0 && errno == EINTR) {
    }
    for (auto it = running.begin(); it != running.end(); ++it) {
      if (it->pid != pid) continue;
      std::ifstream in(it->log);
      for (std::string line; std::getline(in, line);) {
        if (line.empty() || line.find(" cases (" + tier + " tier)") != std::string::npos) continue;
        std::cout << line << "\n";
      }
      std::cout.flush();
      fs::remove(it->log);
      const int rc = WIFEXITED(status) ? WEXITSTATUS(status) : kExitError;
      if (rc == kExitError || rc < 0 || (rc != 0 && rc != kExitFail && rc != kExitSkip)) ++n_error_exit;
      if (rc == kExitFail) ++n_fail_exit;
      if (rc != 0 && rc != kExitFail && rc != kExitSkip && rc != kExitError) {
        std::cout << "ERROR           " << cases[it->index].id << "  (worker exit code " << rc << ")\n";
      }
      running.erase(it);
      return;
    }
  };
  while (next < files.size() || !running.empty()) {
    if (next < files.size() && static_cast<int>(running.size()) < jobs) {
      std::vector<std::string> argv = {self, "run", files[next].string(), "--tier", tier, "--out", out.string()};
      argv.insert(argv.end(), pass_through.begin(), pass_through.end());
      if (strict) argv.push_back("--strict");
      const fs::path log = out / (".worker-" + std::to_string(::getpid()) + "-" + std::to_string(next) + ".log");
      posix_spawn_file_actions_t fa;
      posix_spawn_file_actions_init(&fa);
      posix_spawn_file_actions_addopen(&fa, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      posix_spawn_file_actions_addopen(&fa, 2, "/dev/null", O_WRONLY, 0);
      std::vector<char*> args;
      for (auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
      args.push_back(nullptr);
      pid_t pid = 0;
      const int rc = posix_spawn(&pid, self.c_str(), &fa, nullptr, args.data(), environ);
      posix_spawn_file_actions_destroy(&fa);
      if (rc != 0) throw std::runtime_error("cannot start a worker for " + cases[next].id);
      std::cerr << "run " << cases[next].id << " (" << tier << ", worker " << pid << ")\n";
      running.push_back({pid, next, log});
      ++next;
    } else {
      finish_one();
    }
  }
  merge_checks_json(out);
  CaseTally tally;
  for (const auto& c : cases) {
    std::string st = "ERROR";
    std::ifstream in(out / (c.id + ".json"));
    if (in) {
      try {
        st = json::parse(in).value("status", std::string("ERROR"));
      } catch (const std::exception&) {
      }
    }
    tally.add(st);
  }
  tally.print(cases.size(), tier + " tier, " + std::to_string(jobs) + " workers", out);
  if (tally.error > 0 || n_error_exit > 0) return kExitError;
  if (n_fail_exit > 0) return kExitFail;
  return 0;
}

int cmd_run(const std::vector<std::string>& ids, const std::string& paper, const std::string& tier_opt,
            const fs::path& out, bool ctest_mode, bool strict, int jobs, const std::vector<std::string>& pass_through) {
  const std::string tier = tier_opt.empty() ? "quick" : tier_opt;
  const std::vector<fs::path> files = select_case_files(ids, paper, !tier_opt.empty() && ids.empty());
  if (files.empty()) throw InputError("run", "no cases selected (give case ids, --paper or --tier)");
  require_output_dir(out, "--out");
  // Validate everything first: a bad case writes nothing.
  std::vector<CaseSpec> cases;
  std::vector<fs::path> case_files;
  for (const auto& f : files) {
    CaseSpec c = load_case(f, tier);
    if (!tier_opt.empty() && ids.empty() && !c.in_tier(tier)) continue;
    cases.push_back(std::move(c));
    case_files.push_back(f);
  }
  if (jobs > 1 && cases.size() > 1 && !ctest_mode) {
    return run_cases_in_parallel(case_files, cases, tier, out, strict, jobs, pass_through);
  }
  for (const fs::path& d : {out, fs::path(run_cache_dir())}) {
    if (const std::size_t n = remove_stale_temporaries(d)) {
      std::cerr << "removed " << n << " temporary file(s) of killed runs from " << d.string() << "\n";
    }
  }
  int unexpected = 0;
  CaseTally tally;
  bool all_ni = true;
  for (const auto& c : cases) {
    std::cerr << "run " << c.id << " (" << tier << ")\n";
    Progress progress(true);
    CaseResult r = run_case(c, tier, [&](double f, const std::string& m) { progress(f, m); });
    if (c.implemented()) {
      all_ni = false;
      write_hdf5(c, r, out);
    }
    write_case_json(out, c, r);
    for (const auto& ch : r.checks) {
      if (ch.status == "FAIL") {
        const bool known = !ch.known_failure.empty();
        if (!known || strict) ++unexpected;
        std::cout << "  FAIL" << (known ? " (known)" : "") << " " << c.id << " " << ch.key << ": ";
        if (ch.has_value) {
          std::cout << "value " << fmt(ch.value) << " vs reference "
                    << (ch.is_range ? "[" + fmt(ch.lower) + ", " + fmt(ch.upper) + "]" : fmt(ch.reference)) << " "
                    << ch.units << " (error " << fmt(ch.error) << ", tolerance " << fmt(ch.tolerance)
                    << (ch.relative_tol ? " rel" : "") << ")";
        } else {
          std::cout << ch.message;  // an output the run does not define: no value to compare
        }
        std::cout << (known ? " — " + ch.known_failure : "") << "\n";
      } else if (ch.status == "NOT RUN" || ch.status == "ERROR" || ch.status == "INCONCLUSIVE") {
        std::cout << "  " << ch.status << " " << c.id << " " << ch.key << ": " << ch.message << "\n";
      }
    }
    for (const auto& sr : r.series) {
      if (!sr.error.empty()) std::cout << "  ERROR " << c.id << " series '" << sr.name << "': " << sr.error << "\n";
    }
    const std::string& s = r.status;
    tally.add(s);
    std::cout << std::left << std::setw(16) << s << c.id << "  (" << r.checks.size() << " checks, "
              << fmt(r.wall_time_s, 3) << " s)\n";
  }
  merge_checks_json(out);
  tally.print(cases.size(), tier + " tier", out);
  if (tally.error > 0) return kExitError;
  if (unexpected > 0) return kExitFail;
  if (ctest_mode && all_ni) return kExitSkip;
  return 0;
}

// `cutbench audit`: every counted check must be able to fail. Static rules over every case file (both
// tiers) and the perturbation audit that each `cutbench run` stores in its records (`audit`), read
// from DIR and from the paper-resolution records. Exit 1 when a reproduction or validation check
// is vacuous; consistency and verification checks found so are listed apart.
int cmd_audit(const std::vector<std::string>& ids, const std::string& paper, const fs::path& results, bool as_json) {
  const std::vector<fs::path> files = select_case_files(ids, paper, ids.empty());
  json found = json::array();
  std::size_t counted = 0, perturbed = 0;
  std::set<std::string> seen;  // case|key already flagged
  auto flag = [&](const std::string& id, const std::string& key, const std::string& kind, const std::string& why,
                  const std::string& where) {
    if (!seen.insert(id + "|" + key).second) return;
    found.push_back({{"case", id}, {"key", key}, {"kind", kind}, {"why", why}, {"from", where},
                     {"vacuous", kind == "reproduction" || kind == "validation"}});
  };
  for (const auto& f : files) {
    std::map<std::string, std::string> kinds;
    for (const std::string tier : {"quick", "full"}) {
      const CaseSpec c = load_case(f, tier);
      for (const auto& cs : c.checks) {
        kinds[cs.key] = cs.kind;
        if (tier == "quick" && (cs.kind == "reproduction" || cs.kind == "validation")) ++counted;
        if (const std::string why = audit_static(c, cs); !why.empty()) flag(c.id, cs.key, cs.kind, why, "case file");
      }
      const fs::path rec_path = tier == "full" ? source_root() / "reports" / "full_tier" / c.paper / (c.item_id + ".json")
                                               : results / c.paper / (c.item_id + ".json");
      std::ifstream in(rec_path);
      if (!in) continue;
      json rec;
      try {
        rec = json::parse(in);
      } catch (const json::exception&) {
        continue;
      }
      const bool audited = rec.value("audited", false);
      for (const auto& ch : rec.value("checks", json::array())) {
        const std::string key = ch.value("key", std::string());
        if (!kinds.count(key)) continue;  // a check the case file no longer has
        const std::string st = ch.value("status", std::string());
        if (audited && (st == "PASS" || st == "FAIL")) ++perturbed;
        const std::string why = ch.value("audit", std::string());
        if (!why.empty()) flag(c.id, key, kinds[key], why, rec_path.lexically_relative(source_root()).string());
      }
    }
  }
  std::size_t vacuous = 0;
  for (const auto& j : found) vacuous += j["vacuous"].get<bool>() ? 1 : 0;
  if (as_json) {
    std::cout << json({{"counted_checks", counted}, {"perturbed_records", perturbed}, {"vacuous", vacuous},
                       {"flagged", found}})
                     .dump(2)
              << "\n";
  } else {
    for (const auto& j : found) {
      std::cout << (j["vacuous"].get<bool>() ? "VACUOUS " : "apart   ") << j["case"].get<std::string>() << " "
                << j["key"].get<std::string>() << " (" << j["kind"].get<std::string>()
                << "): " << j["why"].get<std::string>() << " [" << j["from"].get<std::string>() << "]\n";
    }
    std::cout << files.size() << " cases, " << counted << " reproduction/validation checks (quick tier); "
              << perturbed << " check records perturbation-audited; " << vacuous
              << " vacuous reproduction/validation checks"
              << (found.size() > vacuous ? ", " + std::to_string(found.size() - vacuous) +
                                               " verification/consistency checks listed apart"
                                         : std::string())
              << "\n";
  }
  return vacuous > 0 ? kExitFail : 0;
}

// `cutbench records [--paper P] [--refresh]`: the paper-resolution records and their verdicts;
// --refresh re-judges them against the case files as they are now (refresh_record) and rewrites them.
int cmd_records(const std::string& paper, bool refresh) {
  const fs::path dir = source_root() / "reports" / "full_tier";
  int n = 0;
  for (const auto& file : discover_case_files(source_root())) {
    const std::string p = file.parent_path().filename().string();
    if (!paper.empty() && p != paper) continue;
    const fs::path rec_path = dir / p / (file.stem().string() + ".json");
    if (!fs::exists(rec_path)) continue;
    std::ifstream in(rec_path);
    json rec;
    try {
      rec = json::parse(in);
    } catch (const json::exception& e) {
      throw InputError(rec_path.string(), std::string("not a JSON record: ") + e.what());
    }
    const CaseSpec spec = load_case(file, "full");
    ++n;
    if (!refresh) {
      std::cout << std::left << std::setw(28) << spec.id << verdict_word(case_verdicts("", spec)["paper_resolution"])
                << "\n";
      continue;
    }
    std::vector<std::string> changes;
    const json out = refresh_record(rec, spec, &changes);
    write_atomic(rec_path, out.dump(1) + "\n");
    std::cout << spec.id << ": " << out["status"].get<std::string>()
              << (changes.empty() ? std::string(", unchanged") : std::string()) << "\n";
    for (const auto& c : changes) std::cout << "  " << c << "\n";
  }
  std::cout << n << " paper-resolution records" << (refresh ? " refreshed" : "") << "\n";
  return 0;
}

json param_json(const ParamSpec& p) {
  json pj = {{"name", p.name}, {"kind", kind_name(p.kind)}, {"unit", si_unit(p.dim)}, {"description", p.description},
             {"range", describe_range(p)}};
  if (!p.default_value) {
    pj["default"] = nullptr;
  } else if (std::isnan(*p.default_value)) {
    pj["default"] = "unset";
  } else if (p.kind == ParamKind::option) {
    pj["default"] = format_param_value(p, *p.default_value);
  } else if (p.kind == ParamKind::boolean) {
    pj["default"] = *p.default_value == 1.0;
  } else {
    pj["default"] = *p.default_value;
  }
  for (const auto& o : p.options) pj["options"].push_back({{"name", o.name}, {"description", o.description}});
  return pj;
}

json outputs_json(const std::vector<OutputSpec>& outputs) {
  json out = json::array();
  for (const auto& o : outputs) out.push_back({{"name", o.name}, {"unit", si_unit(o.dim)}, {"description", o.description}});
  return out;
}

json describe_json(const ModelSpec& m) {
  json j = {{"name", m.name}, {"type", "model"}, {"description", m.description}, {"source", m.source},
            {"params", json::array()}};
  for (const auto& p : m.params) j["params"].push_back(param_json(p));
  j["outputs"] = outputs_json(m.outputs);
  return j;
}

json describe_json(const SolverSpec& sv) {
  json j = {{"name", sv.name}, {"type", "solver"}, {"method", solver_method(sv.name)}, {"description", sv.description},
            {"source", sv.source}, {"checkpoints", sv.checkpoints}, {"params", json::array()}};
  for (const auto& p : sv.params) j["params"].push_back(param_json(p));
  j["outputs"] = outputs_json(sv.scalars);
  j["tables"] = json::array();
  for (const auto& t : sv.tables) {
    json tj = {{"name", t.name}, {"description", t.description}, {"columns", json::array()}};
    for (const auto& c : t.columns) tj["columns"].push_back({{"name", c.name}, {"unit", c.unit}, {"description", c.description}});
    j["tables"].push_back(tj);
  }
  return j;
}

void print_described(const json& j) {
  std::cout << j["name"].get<std::string>() << " (" << j["type"].get<std::string>() << ") — "
            << j["description"].get<std::string>() << "\n  source: " << j["source"].get<std::string>() << "\n";
  if (j.contains("checkpoints")) {
    std::cout << "  checkpoints: "
              << (j["checkpoints"].get<bool>() ? "yes (run --run-cache DIR --checkpoint-minutes M resumes exactly)"
                                               : "no (its runs are short)")
              << "\n";
  }
  std::cout << "  params:\n";
  for (const auto& p : j["params"]) {
    std::cout << "    " << std::left << std::setw(24) << p["name"].get<std::string>() << ' ' << std::setw(8)
              << p["kind"].get<std::string>() << std::setw(8) << p["unit"].get<std::string>()
              << p["description"].get<std::string>() << "; " << p["range"].get<std::string>();
    if (p["default"].is_null()) {
      std::cout << "; required";
    } else {
      std::cout << "; default ";
      if (p["default"].is_string()) {
        std::cout << p["default"].get<std::string>();
      } else if (p["default"].is_number() && p["unit"] == "rad") {
        std::cout << fmt(p["default"].get<double>() * 180.0 / M_PI) << " deg";
      } else if (p["default"].is_number()) {
        std::cout << fmt(p["default"].get<double>());
      } else {
        std::cout << p["default"].dump();
      }
    }
    std::cout << "\n";
    if (p.contains("options")) {
      for (const auto& o : p["options"]) {
        std::cout << "        \"" << o["name"].get<std::string>() << "\": " << o["description"].get<std::string>() << "\n";
      }
    }
  }
  std::cout << "  outputs:\n";
  for (const auto& o : j["outputs"]) {
    std::cout << "    " << std::left << std::setw(22) << o["name"].get<std::string>() << std::setw(8)
              << o["unit"].get<std::string>() << o["description"].get<std::string>() << "\n";
  }
  if (j.contains("tables")) {
    for (const auto& t : j["tables"]) {
      std::cout << "  table " << t["name"].get<std::string>() << ": " << t["description"].get<std::string>() << "\n";
      for (const auto& c : t["columns"]) {
        std::cout << "    " << std::left << std::setw(22) << c["name"].get<std::string>() << std::setw(8)
                  << c["unit"].get<std::string>() << c["description"].get<std::string>() << "\n";
      }
    }
  }
}

int cmd_eval_list(bool as_json) {
  json all = json::array();
  for (const auto& m : ModelRegistry::instance().all()) all.push_back(describe_json(m));
  if (as_json) {
    std::cout << all.dump(2) << "\n";
    return 0;
  }
  for (const auto& j : all) print_described(j);
  return 0;
}

// `cutbench describe [NAME]`: one model or solver in full, or the list of every one.
int cmd_describe(const std::string& name, bool as_json) {
  if (name.empty()) {
    json all = json::array();
    for (const auto& m : ModelRegistry::instance().all()) {
      all.push_back({{"name", m.name}, {"type", "model"}, {"description", m.description}});
    }
    for (const auto& sv : SolverRegistry::instance().all()) {
      all.push_back({{"name", sv.name}, {"type", "solver"}, {"method", solver_method(sv.name)}, {"description", sv.description}});
    }
    if (as_json) {
      std::cout << all.dump(2) << "\n";
      return 0;
    }
    for (const auto& j : all) {
      std::cout << std::left << std::setw(28) << j["name"].get<std::string>() << std::setw(8)
                << j["type"].get<std::string>() << j["description"].get<std::string>() << "\n";
    }
    return 0;
  }
  json j;
  if (const auto* m = ModelRegistry::instance().find(name)) {
    j = describe_json(*m);
  } else if (const auto* sv = SolverRegistry::instance().find(name)) {
    j = describe_json(*sv);
  } else {
    throw InputError("name", "no model or solver '" + name + "' in this build (see `cutbench describe`)");
  }
  if (as_json) {
    std::cout << j.dump(2) << "\n";
  } else {
    print_described(j);
  }
  return 0;
}

// An applicable model whose output is not finite has overflowed for these inputs: an ERROR (exit 3).
int overflowed(const ModelSpec& m, const ModelResult& r) {
  if (!r.applicable) return 0;
  for (const auto& o : m.outputs) {
    const auto it = r.outputs.find(o.name);
    if (it != r.outputs.end() && !std::isfinite(it->second)) {
      std::cerr << "cutbench: ERROR: output '" << o.name << "' of " << m.name
                << " is not finite for these inputs (overflow)\n";
      return kExitError;
    }
  }
  return 0;
}

int cmd_eval(const std::string& model, const std::vector<std::string>& args, bool as_json) {
  const ModelSpec& m = ModelRegistry::instance().get(model);
  const Values given = parse_assignments(args, m.params, model);
  const ModelResult r = evaluate_model(m, given);
  const Values params = validate_params(m, given);
  if (as_json) {
    json j = {{"model", model}, {"applicable", r.applicable}};
    for (const auto& [k, v] : params) j["inputs"][k] = std::isfinite(v) ? json(v) : json(nullptr);
    for (const auto& o : m.outputs) {
      const double v = r.outputs.count(o.name) ? r.outputs.at(o.name) : nan_value();
      j["outputs"][o.name] = std::isfinite(v) ? json(v) : json(nullptr);
      j["units"][o.name] = si_unit(o.dim);
    }
    if (!r.note.empty()) j["note"] = r.note;
    std::cout << j.dump(2) << "\n";
    return overflowed(m, r);
  } else {
    if (!r.applicable) std::cout << "not applicable: " << r.note << "\n";
    for (const auto& o : m.outputs) {
      const double v = r.outputs.count(o.name) ? r.outputs.at(o.name) : nan_value();
      std::cout << std::left << std::setw(18) << o.name << std::setw(16) << fmt(v, 10) << si_unit(o.dim) << "\n";
    }
  }
  return overflowed(m, r);
}

// Steps a resumed run did before this process: the solvers' note "resumed from a checkpoint at
// step N" (0 when the run did not resume).
double resumed_steps(const RunOutput& r) {
  const std::string tag = "resumed from a checkpoint at step ";
  for (const auto& n : r.notes) {
    const auto p = n.find(tag);
    if (p != std::string::npos) return std::strtod(n.c_str() + p + tag.size(), nullptr);
  }
  return 0.0;
}

// `cutbench bench NAME ... --state FILE`: a solver state in the middle of a run, so that the speed
// of the part that matters (a cut under way, not the start on a regular lattice) can be timed
// again and again, and with different builds. Without FILE the run stops at its first checkpoint,
// after `state_minutes`, and leaves it in FILE; with FILE it resumes from it and runs to the end.
// The key is the solver and its parameters, not the source identity: a bench state is meant to be
// loaded by other builds (a solver whose state layout changed rejects it with an error).
struct BenchState {
  std::string file;
  double minutes = 10.0;
};

int cmd_bench(const std::string& name, const std::vector<std::string>& args, int repeat, const fs::path& out,
              const BenchState& state) {
  json report = {{"bench", name}, {"software", software_version()}, {"date", utc_now_iso()}};
#ifdef _OPENMP
  report["threads"] = omp_get_max_threads();
#endif
  if (name == "analytic") {
    // Throughput of every analytic model at its defaults plus representative inputs from cases.
    std::size_t evals = 0, points = 0;
    const auto t0 = std::chrono::steady_clock::now();
    for (int rep = 0; rep < std::max(1, repeat); ++rep) {
      for (const auto& file : discover_case_files(source_root())) {
        CaseSpec c = load_case(file, "full");
        if (!c.implemented() || c.solver != "analytic") continue;
        const CaseResult r = run_case(c, "full", nullptr);
        for (const auto& sr : r.series) points += sr.table.rows();
        ++evals;
      }
    }
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    report["analytic_cases_run"] = evals;
    report["model_evaluations"] = points;
    report["wall_time_s"] = wall;
    report["evaluations_per_s"] = static_cast<double>(points) / wall;
    std::cout << "analytic: " << evals << " case runs (full tier), " << points << " model evaluations in "
              << fmt(wall, 4) << " s (" << fmt(static_cast<double>(points) / wall, 4) << " evaluations/s)\n";
  } else {
    const SolverSpec* sv = SolverRegistry::instance().find(name);
    if (!sv) sv = SolverRegistry::instance().find(name + "_cutting");  // `bench mpm` = mpm_cutting
    if (!sv) {
      std::string known = "analytic";
      for (const auto& s : SolverRegistry::instance().all()) known += ", " + s.name;
      throw InputError("bench", "unknown benchmark '" + name + "' (available: " + known + ")");
    }
    const Values params = validate_params(ModelSpec{sv->name, "", "", sv->params, {}, {}},
                                          parse_assignments(args, sv->params, name));
    Progress progress(true);
    std::string state_key;
    bool resume = false;
    if (!state.file.empty()) {
      if (!(state.minutes > 0.0)) throw InputError("--state-minutes", "must be > 0 minutes");
      state_key = "bench state|" + sv->name + params_key(params);
      resume = fs::exists(state.file);
      if (resume && !read_checkpoint({state.file, state_key, 0.0, false}, [](BinaryReader&) {}))
        throw InputError("--state", "'" + state.file + "' is not a state of bench " + sv->name +
                                        " with these parameters (or it is corrupt); remove it to write a new one");
      report["state"] = {{"file", state.file}, {"mode", resume ? "resume" : "write"}};
    }
    for (int rep = 0; rep < std::max(1, repeat); ++rep) {
      const auto t0 = std::chrono::steady_clock::now();
      RunOutput r;
      if (!state.file.empty()) {
        // resume: never write (the interval is effectively infinite); write: stop after the first
        const CheckpointSpec spec{state.file, state_key, resume ? 1e300 : 60.0 * state.minutes, !resume};
        CheckpointScope scope(spec);
        try {
          r = sv->run(params, [&](double f, const std::string& m) { progress(f, m); });
        } catch (const CheckpointStop& e) {
          const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
          std::cout << name << ": state written to " << state.file << " after " << fmt(wall, 4) << " s (" << e.what()
                    << ")\n";
          return 0;
        }
        if (!resume)
          std::cout << name << ": the run ended before " << fmt(state.minutes, 4) << " min; no state written\n";
      } else {
        r = sv->run(params, [&](double f, const std::string& m) { progress(f, m); });
      }
      const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      json rj = {{"wall_time_s", wall}};
      if (r.scalars.count("steps")) {
        // steps of this process (a resumed run counts from its state) and their rate per particle
        const double steps = r.scalars.at("steps") - resumed_steps(r);
        rj["steps_timed"] = steps;
        std::cout << name << " run " << rep + 1 << ": " << fmt(steps, 10) << " steps timed";
        for (const char* count : {"particles", "nodes"})
          if (r.scalars.count(count)) {
            const double rate = steps * r.scalars.at(count) / wall;
            rj[std::string(count) == "particles" ? "particle_steps_per_s" : "node_steps_per_s"] = rate;
            std::cout << ", " << fmt(rate / 1e6, 4) << " M " << (std::string(count) == "particles" ? "particle" : "node")
                      << "-steps/s";
          }
        std::cout << "\n";
      }
      for (const auto& [k, v] : r.scalars) rj["scalars"][k] = std::isfinite(v) ? json(v) : json(nullptr);
      report["runs"].push_back(rj);
      std::cout << name << " run " << rep + 1 << ": " << fmt(wall, 4) << " s\n";
      for (const auto& [k, v] : r.scalars) std::cout << "  " << std::left << std::setw(28) << k << fmt(v) << "\n";
    }
  }
  write_atomic(out / "bench" / (name + ".json"), report.dump(2) + "\n");
  return 0;
}

// The solver runs the selected cases compute at `tier` and which of them `dir` holds already
// (stored), holds a checkpoint of (resumes) or lacks (to compute).
int cmd_runs_plan(const std::string& dir, const std::vector<std::string>& ids, const std::string& paper,
                  const std::string& tier, bool as_json, bool compute, const std::vector<std::string>& only_series,
                  const std::vector<std::string>& only_runs, const cli::SlurmOptions& slurm, double checkpoint_minutes,
                  bool skip_running, bool all_cases) {
  const std::vector<fs::path> files = select_case_files(ids, paper, all_cases);
  if (compute && !slurm.dry_run) set_run_cache_dir(dir);  // creates it (an input error when it cannot be written)
  std::vector<std::string> case_ids;
  std::map<std::string, StoredRun> stored;
  for (auto& s : scan_run_store(dir)) stored[s.file] = std::move(s);
  struct Item {
    std::string label;  // case, series, point
    PlannedRun run;
    std::string state;
  };
  std::vector<Item> items;
  json all = json::array();
  for (const auto& f : files) {
    const CaseSpec c = load_case(f, tier);
    if (!c.in_tier(tier)) continue;
    case_ids.push_back(c.id);
    std::size_t n_stored = 0, n_ckpt = 0, n_todo = 0, n_running = 0;
    json runs = json::array();
    const auto planned = planned_runs(c);
    // the parameters that tell this case's runs apart (shown in the listing)
    std::map<std::string, std::set<double>> values;
    for (const auto& p : planned) {
      for (const auto& [k, v] : p.params) values[k].insert(v);
    }
    for (const auto& p : planned) {
      std::string state = planned_run_state(p, stored);
      double done = -1.0;  // fraction done of a running or checkpointed run (its progress log)
      if (state != "stored" && !p.file.empty()) {  // a live process holds its lock: being computed now
        const std::string run_path = (fs::path(dir) / p.file).string();
        const std::string holder = run_lock_holder(run_path);
        if (!holder.empty()) {
          state = "running (" + holder + ")";
          done = run_fraction_done(run_path, true);
        } else if (state == "checkpoint") {  // what a resume starts from
          done = run_fraction_done(run_path, false);
        }
      }
      (state == "stored" ? n_stored : state == "checkpoint" ? n_ckpt : state.rfind("running", 0) == 0 ? n_running : n_todo)++;
      json params = json::object();
      std::string distinct;
      for (const auto& [k, v] : p.params) {
        params[k] = v;
        if (values[k].size() > 1) distinct += (distinct.empty() ? "" : " ") + k + "=" + fmt(v, 6);
      }
      json entry = {{"series", p.series}, {"point", p.point}, {"solver", p.solver}, {"file", p.file},
                    {"state", state}, {"params", params}, {"distinct", distinct}};
      if (done >= 0.0) entry["fraction_done"] = done;
      runs.push_back(std::move(entry));
      items.push_back({c.id + " " + p.series + " " + std::to_string(p.point), p, state});
    }
    all.push_back({{"case", c.id}, {"tier", tier}, {"runs", runs}});
    if (as_json) continue;
    std::cout << c.id << " (" << tier << "): " << runs.size() << " solver run(s), " << n_stored << " stored, " << n_running
              << " running, " << n_ckpt << " with a checkpoint, " << n_todo << " to compute\n";
    for (const auto& r : runs) {
      std::string shown = r["state"].get<std::string>();
      if (r.contains("fraction_done")) {
        shown += ", " + std::to_string(static_cast<int>(std::floor(100.0 * r["fraction_done"].get<double>()))) + " % done";
      }
      std::cout << "  " << std::left << std::setw(24) << (r["series"].get<std::string>() + " " +
                                                             std::to_string(r["point"].get<std::size_t>()))
                << std::setw(static_cast<int>(std::max<std::size_t>(14, shown.size() + 2))) << shown
                << std::setw(36) << r["file"].get<std::string>() << r["distinct"].get<std::string>() << "\n";
    }
  }
  if (as_json) std::cout << all.dump(2) << "\n";
  if (!compute) return 0;
  // Compute what is missing, in the order listed (cases as given, then series order), each run
  // stored as soon as it finishes; runs shared between cases are computed once. A run that another
  // process is computing when its turn comes goes to the back of the queue (and is waited for
  // when nothing else is left), so that copies of this command on one store work on different runs.
  std::set<std::string> done;
  int failed = 0;
  std::deque<Item> queue;
  for (const auto& it : items) {
    const PlannedRun& p = it.run;
    if (p.file.empty() || it.state == "stored" || done.count(p.file)) continue;
    if (!only_series.empty() && std::find(only_series.begin(), only_series.end(), p.series) == only_series.end()) continue;
    if (!only_runs.empty() && std::find(only_runs.begin(), only_runs.end(), p.file) == only_runs.end()) continue;
    done.insert(p.file);
    queue.push_back(it);
  }
  if (slurm.enabled) {
    cli::SlurmPlan plan;
    plan.store = fs::absolute(dir).lexically_normal().string();
    plan.case_ids = case_ids;
    plan.tier = tier;
    plan.checkpoint_minutes = checkpoint_minutes;
    for (const auto& it : queue) plan.runs.push_back(it.run.file);
    return cli::submit_slurm(plan, slurm);
  }
  std::size_t deferred = 0;  // runs passed over in a row because another process holds them
  while (!queue.empty()) {
    const Item it = queue.front();
    queue.pop_front();
    const PlannedRun& p = it.run;
    if (run_in_progress((fs::path(dir) / p.file).string())) {
      if (skip_running) {
        std::cout << "skipped " << p.file << " (" << it.label << "): " << run_lock_holder((fs::path(dir) / p.file).string())
                  << " is computing it\n";
        continue;
      }
      if (deferred <= queue.size()) {
        queue.push_back(it);
        ++deferred;
        continue;
      }
    }
    deferred = 0;
    std::cerr << "compute " << it.label << " -> " << p.file << (it.state == "checkpoint" ? " (resuming)" : "") << "\n";
    Progress progress(true);
    const auto t0 = std::chrono::steady_clock::now();
    try {
      solver_run(*SolverRegistry::instance().find(p.solver), p.params,
                 [&](double f, const std::string& m) { progress(f, it.label + ": " + m); });
    } catch (const InputError&) {
      throw;
    } catch (const std::exception& e) {  // a failed run (its checkpoint stays); go on with the others
      std::cout << "FAILED " << p.file << " (" << it.label << "): " << e.what() << "\n";
      ++failed;
      continue;
    }
    std::cout << "stored " << p.file << " (" << it.label << ", "
              << fmt(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 5) << " s)\n";
  }
  return failed > 0 ? kExitFail : 0;
}

// The stored runs of a run-cache directory: which are usable by this build, with their parameters
// (those that differ from the solver's defaults), provenance and (--results) scalar results.
// --check: exit 1 unless every file is current (reports/full_tier/runs must not keep runs that no
// build of these sources uses).
int cmd_runs(const std::string& dir, bool check, bool as_json, bool scalars, bool upgrade) {
  if (upgrade) {  // rewrite every readable run file in the current format (with its checksum)
    for (const auto& s : scan_run_store(dir)) {
      if (s.kind != "run" || s.key.empty() || s.state.rfind("damaged", 0) == 0 || s.state == "unreadable") continue;
      RunOutput run;
      const std::string path = (fs::path(dir) / s.file).string();
      if (load_run(path, s.key, run)) save_run(path, s.key, run);
    }
  }
  const auto stored = scan_run_store(dir);
  json all = json::array();
  std::size_t not_current = 0;
  for (const auto& s : stored) {
    std::string differing;
    json params = json::object();
    const SolverSpec* sv = SolverRegistry::instance().find(s.solver);
    for (const auto& [name, value] : s.params) {
      params[name] = value;
      const ParamSpec* p = nullptr;
      if (sv) {
        for (const auto& q : sv->params) {
          if (q.name == name) p = &q;
        }
      }
      if (p && p->default_value && std::abs(value - *p->default_value) <= 1e-12 * std::abs(*p->default_value)) continue;
      differing += (differing.empty() ? "" : " ") + name + "=" + fmt(value, 10);
    }
    if (s.state != "current") ++not_current;
    json results = json::object();
    for (const auto& [name, value] : s.scalars) results[name] = value;
    all.push_back({{"file", s.file}, {"kind", s.kind}, {"solver", s.solver}, {"state", s.state},
                   {"identity", s.identity}, {"params", params}, {"differing", differing},
                   {"provenance", s.provenance}, {"scalars", results}});
    if (as_json) continue;
    std::cout << s.file << "  " << s.kind << "  " << s.state << "\n";
    if (!differing.empty()) std::cout << "  " << differing << "\n";
    if (!s.provenance.empty()) std::cout << "  " << s.provenance << "\n";
    if (scalars && !s.scalars.empty()) {
      std::string line;
      for (const auto& [name, value] : s.scalars) {
        const auto u = s.scalar_units.find(name);
        line += (line.empty() ? "" : ", ") + name + " " + fmt(value) +
                (u == s.scalar_units.end() || u->second == "1" ? "" : " " + u->second);
      }
      std::cout << "  results: " << line << "\n";
    }
  }
  if (as_json) {
    std::cout << all.dump(2) << "\n";
  } else {
    std::cout << stored.size() << " stored file(s) in " << dir << ", " << stored.size() - not_current
              << " current, " << not_current << " not usable by this build\n";
  }
  if (check && not_current > 0) {
    std::cerr << "cutbench runs: " << not_current << " stored file(s) in " << dir
              << " are not usable by this build (other solver sources or build settings): delete them, or "
                 "re-run their cases (reports/full_tier/runs/README.md)\n";
    return kExitFail;
  }
  return 0;
}

// Runs a program with an argument vector (no shell: paths are never interpreted) and waits for it.
int run_program(const std::vector<std::string>& argv) {
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = 0;
  if (posix_spawn(&pid, args[0], nullptr, nullptr, args.data(), environ) != 0) return -1;
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) return -1;
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

int cmd_report(const fs::path& results, const fs::path& out) {
  if (!fs::is_directory(results)) throw InputError("--results", "'" + results.string() + "' is not a directory");
  require_output_dir(results, "--results");
  require_output_dir(out, "--out");
  write_manifest(results);
  const std::vector<std::string> argv = {CUTBENCH_PYTHON, (source_root() / "reports" / "make_report.py").string(),
                                         "--root", source_root().string(), "--results", results.string(),
                                         "--out", out.string()};
  const int rc = run_program(argv);
  if (rc != 0) {
    std::cerr << "cutbench report: the report generator failed (exit " << rc << ":";
    for (const auto& a : argv) std::cerr << " '" << a << "'";
    std::cerr << ")\n";
    return kExitFail;
  }
  std::cout << "report: " << (out / "index.html").string() << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"cutbench — validation and benchmark suite for orthogonal-cutting simulation"};
  app.require_subcommand(1);
  app.set_version_flag("--version", software_version());

  bool list_json = false;
  std::string results_dir = "results", list_paper;
  auto* list = app.add_subcommand("list", "Every case with paper, figure/table, tiers and last status");
  list->add_flag("--json", list_json, "JSON output");
  list->add_option("--results", results_dir, "Results directory (for the last status)");
  list->add_option("--paper", list_paper, "Only this paper");

  std::vector<std::string> run_ids;
  std::string run_paper, run_tier, run_out = "results";
  int threads = 0;  // 0: not given (OpenMP's default)
  bool ctest_mode = false, strict = false;
  auto* run = app.add_subcommand("run", "Run cases: write HDF5 results and checks.json");
  run->add_option("cases", run_ids, "Case ids (nairn2015/fig08) or paths to case files");
  run->add_option("--paper", run_paper, "All cases of one paper");
  run->add_option("--tier", run_tier, "Tier: quick (CI) or full (paper resolution)");
  run->add_option("--out", run_out, "Results directory");
  run->add_option("-j,--threads", threads, "OpenMP threads");
  std::string run_cache;
  run->add_option("--run-cache", run_cache,
                  "Directory of finished solver runs, keyed by solver, parameters and the solver's source identity: "
                  "reuse them and store new ones (resume an interrupted full tier; share runs between cases; "
                  "reports/full_tier/runs keeps the full-tier runs)");
  double checkpoint_minutes = 10.0;
  auto* run_ckpt = run->add_option("--checkpoint-minutes", checkpoint_minutes,
                  "With --run-cache: minutes of wall time between two checkpoints of a solver run that supports "
                  "them (MPM, SPH and EFG cutting; `cutbench describe SOLVER` says which); an interrupted run resumes from its last checkpoint (default 10)");
  bool stored_only = false;
  run->add_flag("--stored-only", stored_only,
                "With --run-cache: compute nothing; a case whose runs the store lacks is NOT RUN (evaluate what a "
                "cluster job array stored)");
  double max_memory_gib = kDefaultMaxRunBytes / 1073741824.0;
  run->add_option("--max-memory", max_memory_gib,
                  "GiB one solver run may need (its estimate from the parameters; a larger case is refused "
                  "before anything runs; default 8)");
  run->add_flag("--ctest", ctest_mode, "Exit 77 (skip) when every selected case is NOT IMPLEMENTED");
  run->add_flag("--strict", strict, "Known failures fail the run too");
  int run_jobs = 1;
  run->add_option("--jobs", run_jobs,
                  "Cases run side by side, each in its own process (default 1); with -j threads each: jobs x threads "
                  "should match the cores");

  std::string eval_model;
  std::vector<std::string> eval_args;
  bool eval_json = false, eval_list = false;
  auto* eval = app.add_subcommand("eval", "Evaluate one analytical model (SI units in and out)");
  eval->add_option("model", eval_model, "Model name (see --list)");
  eval->add_option("params", eval_args, "key=value (SI, or with a unit: t1=2mm rake=30deg)");
  eval->add_flag("--json", eval_json, "JSON output");
  eval->add_flag("--list", eval_list, "List every model with its parameters");

  std::string describe_name;
  bool describe_json_out = false;
  auto* describe = app.add_subcommand("describe", "Parameters (kinds, ranges, defaults, options), outputs and tables of "
                                                  "a model or solver; without a name, the list of all");
  describe->add_option("name", describe_name, "Model or solver name");
  describe->add_flag("--json", describe_json_out, "JSON output");

  std::string bench_name, bench_out = "results";
  std::vector<std::string> bench_args;
  int bench_repeat = 1;
  auto* bench = app.add_subcommand("bench", "Throughput benchmarks (analytic, or a solver name)");
  bench->add_option("name", bench_name, "analytic or a solver (e.g. mpm_cutting)")->required();
  bench->add_option("params", bench_args, "key=value solver parameters");
  bench->add_option("--repeat", bench_repeat, "Repetitions");
  bench->add_option("--out", bench_out, "Results directory (bench/<name>.json)");
  bench->add_option("-j,--threads", threads, "OpenMP threads");
  BenchState bench_state;
  bench->add_option("--state", bench_state.file,
                    "Solver state file: resume from it and time the rest of the run; if it does not exist, run "
                    "--state-minutes, write it there and stop");
  bench->add_option("--state-minutes", bench_state.minutes, "With --state: minutes of run before the state is written (default 10)");

  std::string runs_dir = "reports/full_tier/runs";
  bool runs_check = false, runs_json = false;
  auto* runs = app.add_subcommand("runs", "Stored solver runs of a run-cache directory: usable by this build or not");
  runs->add_option("dir", runs_dir, "Run-cache directory (default reports/full_tier/runs)");
  runs->add_flag("--check", runs_check, "Exit 1 unless every stored file is usable by this build");
  runs->add_flag("--json", runs_json, "JSON output");
  bool runs_scalars = false, runs_upgrade = false;
  runs->add_flag("--upgrade", runs_upgrade, "Rewrite every readable run file in the current format (with a checksum)");
  runs->add_flag("--results", runs_scalars, "Also print each stored run's scalar results");
  std::vector<std::string> runs_cases;
  std::string runs_paper, runs_tier = "full";
  runs->add_option("--case", runs_cases, "Plan: the solver runs of these cases and which DIR holds (repeatable)");
  runs->add_option("--paper", runs_paper, "Plan: the solver runs of every case of this paper");
  runs->add_option("--tier", runs_tier, "Plan: tier of the cases (default full); without --case and --paper, every case of that tier");
  bool runs_compute = false;
  std::vector<std::string> runs_series;
  runs->add_flag("--compute", runs_compute,
                 "Plan: compute the runs DIR lacks (resuming checkpoints), store them, evaluate no checks");
  runs->add_option("--series", runs_series, "Plan: only the runs of these series (repeatable)");
  runs->add_option("-j,--threads", threads, "OpenMP threads (with --compute)");
  runs->add_option("--checkpoint-minutes", checkpoint_minutes, "With --compute: minutes between two checkpoints (default 10)");
  runs->add_option("--max-memory", max_memory_gib, "GiB one solver run may need (default 8)");
  std::vector<std::string> runs_only;
  bool runs_skip_running = false;
  runs->add_flag("--skip-running", runs_skip_running,
                 "With --compute: leave the runs another live process is computing to it (default: wait for them at the end)");
  runs->add_option("--run", runs_only, "With --compute: only this run file of the plan (repeatable; a cluster task's run)");
  cli::SlurmOptions slurm;
  runs->add_flag("--slurm", slurm.enabled,
                 "With --compute: submit the runs the store lacks to Slurm as a job array (one run per task, into the "
                 "store, with checkpoints) and a dependent job that records the cases the store then completes");
  runs->add_option("--partition", slurm.partition, "With --slurm: partition");
  runs->add_option("--time", slurm.time, "With --slurm: time limit of one task (default 24:00:00)");
  runs->add_option("--cpus-per-task", slurm.cpus_per_task, "With --slurm: CPUs (OpenMP threads) per run (default 1)");
  runs->add_option("--account", slurm.account, "With --slurm: account");
  runs->add_option("--job-name", slurm.job_name, "With --slurm: job name (default cutbench; scripts <store>/slurm/<name>.*.sh)");
  runs->add_flag("--dry-run", slurm.dry_run, "With --slurm: print the two batch scripts, submit and write nothing");
  runs->add_option("--records", slurm.records, "With --slurm: directory the record job writes the records into (default reports/full_tier)");

  std::vector<std::string> audit_ids;
  std::string audit_paper, audit_results = "results";
  bool audit_json = false;
  auto* audit = app.add_subcommand("audit", "Can every counted check fail? Static rules and the stored perturbation audit");
  audit->add_option("cases", audit_ids, "Case ids (default: every case)");
  audit->add_option("--paper", audit_paper, "Every case of one paper");
  audit->add_option("--results", audit_results, "Results directory of a `cutbench run` (its records carry the audit)");
  audit->add_flag("--json", audit_json, "JSON output");

  std::string records_paper;
  bool records_refresh = false;
  auto* records = app.add_subcommand("records", "The paper-resolution records (reports/full_tier/<paper>/<item>.json)");
  records->add_option("--paper", records_paper, "Only this paper");
  records->add_flag("--refresh", records_refresh,
                    "Re-judge each record against its case file as it is now (values as recorded) and rewrite it");

  std::string report_results = "results", report_out = "report";
  auto* report = app.add_subcommand("report", "Static HTML report from the results directory");
  report->add_option("--results", report_results, "Results directory");
  report->add_option("--out", report_out, "Output directory");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? 0 : kExitBadInput;
  }
  try {
    if (!(checkpoint_minutes > 0.0 && checkpoint_minutes <= 10080.0)) {
      throw InputError("--checkpoint-minutes", "minutes in (0, 10080] (got " + fmt(checkpoint_minutes) + ")");
    }
    if (!(max_memory_gib > 0.0 && max_memory_gib <= 1048576.0)) {
      throw InputError("--max-memory", "GiB in (0, 1048576] (got " + fmt(max_memory_gib) + ")");
    }
    set_max_run_bytes(max_memory_gib * 1073741824.0);
    if (threads < 0 || threads > 1024) throw InputError("-j", "a number of threads in 1..1024 (got " + std::to_string(threads) + ")");
#ifdef _OPENMP
    if (threads > 0) omp_set_num_threads(threads);
#endif
    register_all();
    if (*list) return cmd_list(list_json, results_dir, list_paper);
    if (*run) {
      if (run_ckpt->count() > 0 && run_cache.empty()) {
        throw InputError("--checkpoint-minutes", "checkpoints are kept beside stored runs: give --run-cache DIR too");
      }
      if (stored_only && run_cache.empty()) throw InputError("--stored-only", "evaluates a run store: give --run-cache DIR too");
      set_run_cache_dir(run_cache);
      set_run_cache_stored_only(stored_only);
      set_checkpoint_interval(60.0 * checkpoint_minutes);
      if (run_jobs < 1 || run_jobs > 256) throw InputError("--jobs", "a number of worker processes in 1..256 (got " + std::to_string(run_jobs) + ")");
      std::vector<std::string> pass;  // what each worker of --jobs needs besides the case
      if (!run_cache.empty()) pass.insert(pass.end(), {"--run-cache", run_cache, "--checkpoint-minutes", fmt(checkpoint_minutes, 17)});
      if (stored_only) pass.push_back("--stored-only");
      pass.insert(pass.end(), {"--max-memory", fmt(max_memory_gib, 17)});
      if (threads > 0) pass.insert(pass.end(), {"-j", std::to_string(threads)});
      return cmd_run(run_ids, run_paper, run_tier, run_out, ctest_mode, strict, run_jobs, pass);
    }
    if (*eval) {
      if (eval_list) return cmd_eval_list(eval_json);
      if (eval_model.empty()) throw InputError("model", "give a model name (see `cutbench eval --list`)");
      return cmd_eval(eval_model, eval_args, eval_json);
    }
    if (*describe) return cmd_describe(describe_name, describe_json_out);
    if (*bench) return cmd_bench(bench_name, bench_args, bench_repeat, bench_out, bench_state);
    if (*report) return cmd_report(report_results, report_out);
    if (*records) return cmd_records(records_paper, records_refresh);
    if (*audit) return cmd_audit(audit_ids, audit_paper, audit_results, audit_json);
    if (*runs) {
      // `--tier T` alone plans every case of that tier (the whole paper-resolution tier)
      const bool all_cases = runs_cases.empty() && runs_paper.empty() && runs->get_option("--tier")->count() > 0;
      if (runs_cases.empty() && runs_paper.empty() && !all_cases) {
        if (runs_compute || !runs_series.empty()) throw InputError("--compute", "give the cases: --case C, --paper P or --tier T (every case)");
        return cmd_runs(runs_dir, runs_check, runs_json, runs_scalars, runs_upgrade);
      }
      if (runs_tier != "quick" && runs_tier != "full") throw InputError("--tier", "quick or full");
      if ((slurm.enabled || !runs_only.empty()) && !runs_compute) {
        throw InputError(slurm.enabled ? "--slurm" : "--run", "a plan to compute: give --compute too");
      }
      if (slurm.dry_run && !slurm.enabled) throw InputError("--dry-run", "prints the Slurm scripts: give --slurm too");
      if (slurm.enabled) {
        if (!(slurm.cpus_per_task >= 1 && slurm.cpus_per_task <= 1024)) {
          throw InputError("--cpus-per-task", "a number of CPUs in 1..1024 (got " + std::to_string(slurm.cpus_per_task) + ")");
        }
        const auto word = [](const std::string& s) {
          return std::all_of(s.begin(), s.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.' || c == ':'; });
        };
        if (slurm.job_name.empty() || !word(slurm.job_name)) throw InputError("--job-name", "letters, digits, '_', '-', '.' (got '" + slurm.job_name + "')");
        if (!word(slurm.partition)) throw InputError("--partition", "letters, digits, '_', '-', '.'");
        if (!word(slurm.account)) throw InputError("--account", "letters, digits, '_', '-', '.'");
        if (slurm.time.empty() || !word(slurm.time)) throw InputError("--time", "a Slurm time limit such as 24:00:00 or 2-00:00:00");
      }
      set_checkpoint_interval(60.0 * checkpoint_minutes);
      return cmd_runs_plan(runs_dir, runs_cases, runs_paper, runs_tier, runs_json, runs_compute, runs_series, runs_only,
                           slurm, checkpoint_minutes, runs_skip_running, all_cases);
    }
  } catch (const InputError& e) {
    std::cerr << "cutbench: error: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "cutbench: internal error: " << e.what() << "\n";
    return kExitFail;
  }
  return 0;
}
