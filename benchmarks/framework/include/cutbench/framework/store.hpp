#pragma once
// The results directory: <dir>/<paper>/<item>.h5 (data), <dir>/<paper>/<item>.json (the case's
// check records and status from its last run), <dir>/checks.json (all records merged) and
// <dir>/manifest.json (every case with its metadata and plot specs, for the report).
#include <filesystem>

#include "cutbench/framework/case.hpp"
#include "cutbench/framework/results.hpp"

namespace cutbench::framework {

json read_case_json(const std::filesystem::path& dir, const CaseSpec& spec);  // null if never run
void write_case_json(const std::filesystem::path& dir, const CaseSpec& spec, const CaseResult& r);
void merge_checks_json(const std::filesystem::path& dir);
void write_manifest(const std::filesystem::path& dir);

}  // namespace cutbench::framework
