#include "cutbench/framework/store.hpp"

#include <fstream>
#include <map>
#include <set>

#include "cutbench/common/errors.hpp"
#include "cutbench/framework/run_cache.hpp"
#include "cutbench/framework/runner.hpp"

namespace cutbench::framework {
namespace fs = std::filesystem;

namespace {
fs::path case_json_path(const fs::path& dir, const std::string& paper, const std::string& item) {
  return dir / paper / (item + ".json");
}
}  // namespace

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

void merge_checks_json(const fs::path& dir) {
  json merged = {{"software", software_version()}, {"date", utc_now_iso()}, {"cases", json::array()}};
  json checks = json::array();
  for (const auto& file : discover_case_files(source_root())) {
    const std::string paper = file.parent_path().filename().string();
    std::ifstream in(case_json_path(dir, paper, file.stem().string()));
    if (!in) continue;
    try {
      json c = json::parse(in);
      merged["cases"].push_back({{"case", c["case"]}, {"status", c["status"]}, {"tier", c["tier"]}, {"date", c["date"]}});
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
  for (const auto& p : kPaperIds) {
    try {
      Inventory inv = load_inventory(root, p);
      json items = json::array();
      for (const auto& it : inv.items) {
        items.push_back({{"id", it.id}, {"kind", it.kind}, {"number", it.number}, {"title", it.title}});
      }
      papers[p] = {{"meta", inv.meta}, {"items", items}};
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
  std::map<std::string, std::set<std::string>> paper_total, paper_done, paper_ckpt;  // distinct runs
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
      std::set<std::string> total, done, ckpt;
      for (const auto& p : plan) {
        if (p.file.empty()) continue;  // linked to another series' outputs: not known before running
        total.insert(p.file);
        const std::string state = planned_run_state(p, stored);
        if (state == "stored") done.insert(p.file);
        if (state == "checkpoint") ckpt.insert(p.file);
      }
      if (!total.empty()) j["full_runs"] = {{"total", total.size()}, {"stored", done.size()}, {"checkpoint", ckpt.size()}};
      paper_total[c.paper].insert(total.begin(), total.end());
      paper_done[c.paper].insert(done.begin(), done.end());
      paper_ckpt[c.paper].insert(ckpt.begin(), ckpt.end());
    }
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
    runs[paper] = {{"total", files.size()}, {"stored", paper_done[paper].size()}, {"checkpoint", paper_ckpt[paper].size()}};
  }
  m["full_runs"] = runs;
  write_atomic(dir / "manifest.json", m.dump(1) + "\n");
}

}  // namespace cutbench::framework
