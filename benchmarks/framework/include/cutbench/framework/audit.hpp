#pragma once
// The check audit (`cutbench audit`): a counted check must be able to fail. See audit.cpp.
#include <string>
#include <vector>

#include "cutbench/framework/case.hpp"
#include "cutbench/framework/reference.hpp"
#include "cutbench/framework/results.hpp"
#include "cutbench/framework/runner.hpp"

namespace cutbench::framework {

// Rules that need no data: a literal value, value and reference selecting the same data, a value
// reading an input that its series varies. Empty when none applies.
std::string audit_static(const CaseSpec& spec, const CheckSpec& cs);

// audit_static, then: perturb each column the value reads (scaled, shifted, reversed, a spike or a
// dip at any point; the reference is re-evaluated on the same perturbed data) and re-evaluate.
// Returns why the verdict cannot change ("cannot fail: ..." / "cannot pass: ...") or empty when it
// can. `series` is restored on return.
std::string audit_check(const CaseSpec& spec, const CheckSpec& cs, const CheckRecord& base,
                        std::vector<SeriesResult>& series, ReferenceCache& refs);

}  // namespace cutbench::framework
