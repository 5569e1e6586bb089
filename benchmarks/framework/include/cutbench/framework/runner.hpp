#pragma once
#include <functional>
#include <string>

#include "cutbench/common/solver.hpp"
#include "cutbench/framework/case.hpp"
#include "cutbench/framework/reference.hpp"
#include "cutbench/framework/results.hpp"

namespace cutbench::framework {

// Register every analytic model and solver that this build contains (idempotent).
void register_all();

// Compute the series of a case (analytic models and solver runs) and evaluate its checks.
CaseResult run_case(const CaseSpec& spec, const std::string& tier, const ProgressFn& progress);

// Evaluate the checks of a case against computed series.
std::vector<CheckRecord> evaluate_checks(const CaseSpec& spec, const std::vector<SeriesResult>& series,
                                         ReferenceCache& refs);

// Overall status: NOT IMPLEMENTED; else FAIL if any check failed (documented known failures
// included: they stay visible, they only do not fail the exit code); else PASS if any passed;
// else NOT RUN.
std::string case_status(const CaseSpec& spec, const std::vector<CheckRecord>& checks);

}  // namespace cutbench::framework
