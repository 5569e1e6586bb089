#pragma once
// The results directory: <dir>/<paper>/<item>.h5 (data), <dir>/<paper>/<item>.json (the case's
// check records and status from its last run), <dir>/checks.json (all records merged) and
// <dir>/manifest.json (every case with its metadata and plot specs, for the report).
#include <filesystem>
#include <string>
#include <vector>

#include "cutbench/framework/case.hpp"
#include "cutbench/framework/results.hpp"

namespace cutbench::framework {

// An output directory that can be written: an existing directory, or one whose nearest existing
// ancestor is a writable directory. Checked before anything runs; throws InputError naming `field`.
void require_output_dir(const std::filesystem::path& dir, const std::string& field);

// Temporary files (`*.tmp.<pid>`, `*.<pid>[.<n>].tmp`) left in `dir` (two levels deep) by a
// process that no longer runs, e.g. one killed while writing: removed. Returns how many.
std::size_t remove_stale_temporaries(const std::filesystem::path& dir);

json read_case_json(const std::filesystem::path& dir, const CaseSpec& spec);  // null if never run
void write_case_json(const std::filesystem::path& dir, const CaseSpec& spec, const CaseResult& r);
void merge_checks_json(const std::filesystem::path& dir);

// The two verdicts of a case (the paper-resolution verdict leads everywhere):
//   paper_resolution: the full-tier record reports/full_tier/<paper>/<item>.json, or for an analytic
//     case its last run in `dir` (an analytic evaluation is at paper resolution already); "NOT YET
//     RUN" without either. A record made by other solver sources than this build's is `stale`.
//   regression: the last quick-tier run in `dir` (reduced resolution, a gate against drift).
// Each: {status, basis, counts {kind: {status: n}}, unexpected_failures, date, software, ...}.
json case_verdicts(const std::filesystem::path& dir, const CaseSpec& spec);
// A paper-resolution record re-judged against its case file as it is now (rejudge_check): the
// recorded values kept, every check of the case present (a check added later is NOT RUN), checks
// the case no longer has dropped; `changes` lists each status that changed.
json refresh_record(const json& rec, const CaseSpec& full_spec, std::vector<std::string>* changes);

// Checks counted by kind and status: {"reproduction": {"PASS": 3, "FAIL": 1}, ...}.
json count_checks(const json& checks);
void write_manifest(const std::filesystem::path& dir);

}  // namespace cutbench::framework
