// A test that repeats, larger or longer, code paths that other tests already exercise under the
// sanitizers runs in the release suite only: ASan + UBSan and TSan cost it 5-20x its release time.
// It is reported as skipped there, with the test that covers its paths.
//   BOOST_AUTO_TEST_CASE(name, CUTBENCH_RELEASE_ONLY("paths covered by <test>")) { ... }
#pragma once

#include <boost/test/unit_test.hpp>

namespace cutbench_test {

#ifdef CUTBENCH_SANITIZED_BUILD
inline constexpr bool kSanitizedBuild = true;
#else
inline constexpr bool kSanitizedBuild = false;
#endif

// A precondition rather than enable_if: it still holds when a --run_test filter names the suite.
inline boost::unit_test::decorator::precondition release_only(const char* covered_by) {
  return boost::unit_test::precondition([covered_by](boost::unit_test::test_unit_id) {
    boost::test_tools::assertion_result r(!kSanitizedBuild);
    if (kSanitizedBuild) r.message() << "release suite only (sanitizer build); " << covered_by;
    return r;
  });
}

}  // namespace cutbench_test

#define CUTBENCH_RELEASE_ONLY(covered_by) *cutbench_test::release_only(covered_by)
