#include "cutbench/framework/store.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <fstream>
#include <map>
#include <set>

#include "cutbench/common/errors.hpp"
#include "cutbench/framework/run_cache.hpp"
#include "cutbench/framework/runner.hpp"

// after the project headers: <signal.h> defines a macro `si_value`
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

namespace cutbench::framework {
namespace fs = std::filesystem;

namespace {
fs::path case_json_path(const fs::path& dir, const std::string& paper, const std::string& item) {
  return dir / paper / (item + ".json");
}
}  // namespace

void require_output_dir(const fs::path& dir, const std::string& field) {
  if (dir.empty()) throw InputError(field, "an output directory (an empty path was given)");
  std::error_code ec;
  fs::path where = dir;  // a directory that must accept a new entry: dir, or its nearest existing ancestor
  if (fs::exists(dir, ec)) {
    if (!fs::is_directory(dir, ec)) throw InputError(field, "'" + dir.string() + "' exists and is not a directory");
  } else {
    where = fs::absolute(dir, ec).parent_path();
    while (!fs::exists(where, ec) && where != where.root_path()) where = where.parent_path();
    if (!fs::is_directory(where, ec)) {
      throw InputError(field, "'" + dir.string() + "' cannot be created: '" + where.string() + "' is not a directory");
    }
  }
  // a probe entry, removed at once (permission bits do not tell for root or special file systems)
  const fs::path probe = where / (".cutbench-probe." + std::to_string(::getpid()));
  if (::mkdir(probe.c_str(), 0700) != 0) {
    throw InputError(field, "'" + dir.string() + "' cannot be written ('" + where.string() + "' refuses new entries)");
  }
  ::rmdir(probe.c_str());
}

namespace {
// The writer's pid in a temporary file name: "<name>.tmp.<pid>" (results) or
// "<name>.<pid>[.<n>].tmp" (run files, checkpoints); -1 for any other name.
long temporary_writer(const std::string& name) {
  auto digits = [](const std::string& t) {
    return !t.empty() && t.size() < 12 && std::all_of(t.begin(), t.end(), [](unsigned char c) { return std::isdigit(c); });
  };
  const auto tmp = name.rfind(".tmp.");
  if (tmp != std::string::npos && digits(name.substr(tmp + 5))) return std::stol(name.substr(tmp + 5));
  if (name.size() > 4 && name.compare(name.size() - 4, 4, ".tmp") == 0) {
    std::string rest = name.substr(0, name.size() - 4);  // "<name>.<pid>" or "<name>.<pid>.<n>"
    auto dot = rest.rfind('.');
    if (dot == std::string::npos || !digits(rest.substr(dot + 1))) return -1;
    const std::string last = rest.substr(dot + 1);
    rest.resize(dot);
    dot = rest.rfind('.');
    if (dot != std::string::npos && digits(rest.substr(dot + 1))) return std::stol(rest.substr(dot + 1));
    return std::stol(last);
  }
  return -1;
}
}  // namespace

std::size_t remove_stale_temporaries(const fs::path& dir) {
  std::size_t removed = 0;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return 0;
  for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::recursive_directory_iterator();
       it.increment(ec)) {
    if (it.depth() > 2) it.disable_recursion_pending();
    if (!it->is_regular_file(ec)) continue;
    const long pid = temporary_writer(it->path().filename().string());
    if (pid <= 0 || pid == static_cast<long>(::getpid())) continue;
    if (::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH) continue;  // its writer may be alive
    if (fs::remove(it->path(), ec)) ++removed;
  }
  return removed;
}

json read_case_json(const fs::path& dir, const CaseSpec& spec) {
  std::ifstream in(case_json_path(dir, spec.paper, spec.item_id));
  if (!in) return nullptr;
  try {
    return json::parse(in);
  } catch (const json::exception&) {
    return nullptr;
  }
}

void write_case_json(const fs::path& dir, const CaseSpec& spec, const CaseResult& r) {
  write_atomic(case_json_path(dir, spec.paper, spec.item_id), case_result_to_json(spec, r).dump(2) + "\n");
}

json count_checks(const json& checks) {
  json counts = json::object();
  for (const auto& k : kCheckKinds) counts[k] = json::object();
  if (!checks.is_array()) return counts;
  for (const auto& ch : checks) {
    const std::string kind = ch.value("kind", std::string("reproduction"));
    const std::string status = ch.value("status", std::string("NOT RUN"));
    counts[kind][status] = counts[kind].value(status, 0) + 1;
  }
  return counts;
}

namespace {
json verdict_of(const json& rec, const std::string& basis) {
  json v = {{"status", rec.value("status", std::string("NOT RUN"))},
            {"basis", basis},
            {"tier", rec.value("tier", std::string())},
            {"date", rec.value("date", std::string())},
            {"software", rec.value("software", std::string())},
            {"unexpected_failures", rec.value("unexpected_failures", 0)},
            {"counts", count_checks(rec.value("checks", json::array()))}};
  return v;
}

// "0.1.0+2b41ea00147e" -> "2b41ea00147e" (with "+dirty" kept as a suffix)
std::string commit_of(const std::string& software) {
  const auto plus = software.find('+');
  return plus == std::string::npos ? std::string() : software.substr(plus + 1);
}
}  // namespace

json case_verdicts(const fs::path& dir, const CaseSpec& spec) {
  json out;
  const json last = read_case_json(dir, spec);
  const bool have_last = last.is_object() && last.contains("status");
  json paper = {{"status", spec.implemented() ? "NOT YET RUN" : "NOT IMPLEMENTED"}, {"basis", "none"}};
  if (spec.implemented() && spec.solver == "analytic") {
    if (have_last) paper = verdict_of(last, "analytic evaluation");
  } else if (spec.implemented()) {
    const fs::path rec_path = source_root() / "reports" / "full_tier" / spec.paper / (spec.item_id + ".json");
    std::ifstream in(rec_path);
    if (in) {
      try {
        const json rec = json::parse(in);
        paper = verdict_of(rec, "full-tier record");
        paper["record"] = fs::relative(rec_path, source_root()).string();
        paper["commit"] = commit_of(rec.value("software", std::string()));
        if (rec.contains("recorded")) paper["how"] = rec["recorded"].value("how", std::string());
        const std::string made_by = rec.value("solver_sources", std::string());
        const std::string now = solver_sources(spec.solver);
        paper["stale"] = !now.empty() && made_by != now;
        if (paper["stale"].get<bool>()) {
          paper["stale_reason"] = made_by.empty() ? "the record does not name the solver sources that made it"
                                                  : "made by other " + spec.solver + " sources (commit " +
                                                        paper["commit"].get<std::string>() + ") than this build's";
        }
        const fs::path h5 = rec_path.parent_path() / (spec.item_id + ".h5");
        if (fs::exists(h5)) paper["h5"] = fs::absolute(h5).string();
      } catch (const json::exception&) {
        paper = {{"status", "ERROR"}, {"basis", "full-tier record"}, {"message", "unreadable record " + rec_path.string()}};
      }
    }
  }
  out["paper_resolution"] = paper;
  json reg = {{"status", spec.implemented() ? "NOT RUN" : "NOT IMPLEMENTED"}, {"basis", "none"}, {"tier", "quick"}};
  if (have_last && last.value("tier", std::string()) == "quick") reg = verdict_of(last, "quick tier (reduced resolution)");
  out["regression"] = reg;
  return out;
}

json refresh_record(const json& rec, const CaseSpec& spec, std::vector<std::string>* changes) {
  json out = rec;
  ReferenceCache refs;
  std::map<std::string, json> old;
  for (const auto& ch : rec.value("checks", json::array())) old[ch.value("key", std::string())] = ch;
  std::vector<CheckRecord> records;
  json dropped = json::array();
  for (const auto& cs : spec.checks) {
    const auto it = old.find(cs.key);
    CheckRecord r;
    if (it == old.end()) {
      r = rejudge_check(spec, cs, json::object(), refs);
      r.status = "NOT RUN";
      r.message = "not in the record: the check was added to the case file after the run";
    } else {
      r = rejudge_check(spec, cs, it->second, refs);
      const std::string was = it->second.value("status", std::string());
      if (was == "ERROR") r.status = "ERROR";
      if (changes && was != r.status) changes->push_back(cs.key + ": " + was + " -> " + r.status);
    }
    records.push_back(r);
  }
  for (const auto& [key, ch] : old) {
    if (std::none_of(spec.checks.begin(), spec.checks.end(), [&key = key](const CheckSpec& c) { return c.key == key; })) {
      dropped.push_back(key);
      if (changes) changes->push_back(key + ": removed from the case file");
    }
  }
  json checks = json::array();
  int unexpected = 0;
  for (const auto& r : records) {
    json j = check_to_json(r);
    // the perturbation audit needs the run's data: keep what the run recorded
    if (const auto it = old.find(r.key); it != old.end() && it->second.contains("audit")) j["audit"] = it->second["audit"];
    checks.push_back(j);
    unexpected += (r.status == "FAIL" && r.known_failure.empty()) ? 1 : 0;
  }
  out["checks"] = checks;
  out["unexpected_failures"] = unexpected;
  std::string status = case_status(spec, records);
  if (rec.value("status", std::string()) == "ERROR") status = "ERROR";
  if (changes && status != rec.value("status", std::string())) {
    changes->push_back("case: " + rec.value("status", std::string()) + " -> " + status);
  }
  out["status"] = status;
  if (!spec.claim.empty()) out["claim"] = spec.claim;
  out["solver"] = spec.solver;
  out["refreshed"] = {{"software", software_version()},
                      {"note", "kinds, texts, tolerances, windows and literal references re-read from the case file; "
                               "values and data-derived references as the run recorded them"}};
  if (!dropped.empty()) out["refreshed"]["dropped_checks"] = dropped;
  return out;
}

void merge_checks_json(const fs::path& dir) {
  json merged = {{"software", software_version()}, {"date", utc_now_iso()}, {"cases", json::array()}};
  json checks = json::array();
  for (const auto& file : discover_case_files(source_root())) {
    const std::string paper = file.parent_path().filename().string();
    std::ifstream in(case_json_path(dir, paper, file.stem().string()));
    if (!in) continue;
    try {
      json c = json::parse(in);
      json entry = {{"case", c["case"]}, {"status", c["status"]}, {"tier", c["tier"]}, {"date", c["date"]}};
      try {
        const CaseSpec spec = load_case(file, c.value("tier", std::string("quick")));
        const json v = case_verdicts(dir, spec);
        entry = {{"case", c["case"]},
                 {"paper_resolution", v["paper_resolution"]["status"]},
                 {"paper_resolution_basis", v["paper_resolution"]["basis"]},
                 {"paper_resolution_stale", v["paper_resolution"].value("stale", false)},
                 {"regression", v["regression"]["status"]},
                 {"status", c["status"]}, {"tier", c["tier"]}, {"date", c["date"]}};
      } catch (const std::exception&) {
      }
      merged["cases"].push_back(entry);
      for (const auto& ch : c["checks"]) checks.push_back(ch);
    } catch (const json::exception&) {
    }
  }
  merged["checks"] = checks;
  write_atomic(dir / "checks.json", merged.dump(2) + "\n");
}

void write_manifest(const fs::path& dir) {
  const fs::path root = source_root();
  json m = {{"software", software_version()}, {"date", utc_now_iso()}, {"root", root.string()}};
  json papers = json::object();
  for (const auto& p : paper_ids()) {
    try {
      Inventory inv = load_inventory(root, p);
      json items = json::array();
      for (const auto& it : inv.items) {
        items.push_back({{"id", it.id}, {"kind", it.kind}, {"number", it.number}, {"title", it.title}});
      }
      papers[p] = {{"meta", inv.meta}, {"items", items}};
      const fs::path findings = root / "benchmarks" / p / "FINDINGS.md";
      if (fs::exists(findings)) papers[p]["findings"] = findings.string();
    } catch (const std::exception&) {
      papers[p] = {{"meta", json::object()}, {"items", json::array()}};
    }
  }
  m["papers"] = papers;
  // the full-tier campaign: which solver runs of each case the repository's run store holds
  const fs::path store = root / "reports" / "full_tier" / "runs";
  std::map<std::string, StoredRun> stored;
  if (fs::is_directory(store)) {
    for (auto& s : scan_run_store(store.string())) stored[s.file] = std::move(s);
  }
  std::map<std::string, std::set<std::string>> paper_total, paper_done, paper_ckpt, paper_running;  // distinct runs
  json cases = json::array();
  for (const auto& file : discover_case_files(root)) {
    CaseSpec c = load_case(file, "quick");
    json last = read_case_json(dir, c);
    json j = {{"case", c.id},          {"paper", c.paper},         {"item_id", c.item_id},
              {"item", c.item},        {"title", c.title},         {"requirement", c.requirement},
              {"status", c.implemented() ? "NOT RUN" : "NOT IMPLEMENTED"},
              {"implemented", c.implemented()}, {"reason", c.reason}, {"solver", c.solver},
              {"models", c.models},    {"tiers", c.tiers},         {"assumptions", c.assumptions},
              {"plots", c.plots},      {"tables", c.tables},       {"file", fs::relative(file, root).string()}};
    std::vector<PlannedRun> plan;
    if (c.implemented() && c.in_tier("full")) {
      try {
        plan = planned_runs(load_case(file, "full"));
      } catch (const InputError&) {  // a solver this build lacks (CUTBENCH_SOLVERS=OFF): nothing to count
      }
    }
    if (!plan.empty()) {
      std::set<std::string> total, done, ckpt, running;
      json progress = json::array();  // the runs under way: running (lock held) or checkpointed
      for (const auto& p : plan) {
        if (p.file.empty()) continue;  // linked to another series' outputs: not known before running
        if (!total.insert(p.file).second) continue;
        const std::string state = planned_run_state(p, stored);
        if (state == "stored") {
          done.insert(p.file);
          continue;
        }
        const std::string run_path = (store / p.file).string();
        const bool live = run_in_progress(run_path);
        if (live) running.insert(p.file);
        if (state == "checkpoint") ckpt.insert(p.file);
        if (live || state == "checkpoint") {
          progress.push_back({{"file", p.file}, {"state", live ? "running" : "checkpoint"},
                              {"fraction_done", run_fraction_done(run_path, live)}});
        }
      }
      if (!total.empty()) {
        j["full_runs"] = {{"total", total.size()}, {"stored", done.size()}, {"checkpoint", ckpt.size()},
                          {"running", running.size()}, {"in_progress", progress}};
      }
      paper_total[c.paper].insert(total.begin(), total.end());
      paper_done[c.paper].insert(done.begin(), done.end());
      paper_ckpt[c.paper].insert(ckpt.begin(), ckpt.end());
      paper_running[c.paper].insert(running.begin(), running.end());
    }
    if (!c.claim.empty()) j["claim"] = c.claim;
    j["verdicts"] = case_verdicts(dir, c);
    if (last.is_object()) {
      j["status"] = last.value("status", "NOT RUN");
      j["last_run"] = last;
      const fs::path h5 = dir / c.paper / (c.item_id + ".h5");
      if (fs::exists(h5)) j["h5"] = fs::absolute(h5).string();
    }
    cases.push_back(j);
  }
  m["cases"] = cases;
  json runs = json::object();
  for (const auto& [paper, files] : paper_total) {
    runs[paper] = {{"total", files.size()},
                   {"stored", paper_done[paper].size()},
                   {"checkpoint", paper_ckpt[paper].size()},
                   {"running", paper_running[paper].size()}};
  }
  m["full_runs"] = runs;
  write_atomic(dir / "manifest.json", m.dump(1) + "\n");
}

}  // namespace cutbench::framework
