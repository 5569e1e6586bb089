# Register every case file with ctest: `case:<paper>/<item>` (label quick) and
# `case-full:<paper>/<item>` (label full), with labels paper:<id> and solver:<name>.
# NOT IMPLEMENTED cases exit 77 and show as skipped.
file(GLOB CUTBENCH_CASE_FILES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/benchmarks/*/*.toml)
foreach(case_file ${CUTBENCH_CASE_FILES})
  get_filename_component(item ${case_file} NAME_WE)
  get_filename_component(paper_dir ${case_file} DIRECTORY)
  get_filename_component(paper ${paper_dir} NAME)
  file(STRINGS ${case_file} solver_line REGEX "^solver *=")
  file(STRINGS ${case_file} tiers_line REGEX "^tiers *=")
  string(REGEX REPLACE "^solver *= *\"([a-z_]+)\".*" "\\1" solver "${solver_line}")
  foreach(tier quick full)
    if(tiers_line MATCHES "\"${tier}\"")
      if(tier STREQUAL "quick")
        set(test_name "case:${paper}/${item}")
        # the quick-tier cases share their solver runs (keyed by solver, parameters and the solver's
        # source identity) through a run cache in the build tree: a run two cases need is computed once
        set(share --run-cache ${CMAKE_BINARY_DIR}/runs-quick)
      else()
        set(test_name "case-full:${paper}/${item}")
        set(share "")
      endif()
      add_test(NAME ${test_name}
               COMMAND cutbench run ${paper}/${item} --tier ${tier} --out ${CMAKE_BINARY_DIR}/results-${tier} ${share} --ctest)
      set_tests_properties(${test_name} PROPERTIES
        LABELS "${tier};paper:${paper};solver:${solver}"
        FIXTURES_SETUP "results_${tier}"
        SKIP_RETURN_CODE 77
        ENVIRONMENT "OMP_NUM_THREADS=${CUTBENCH_TEST_THREADS};OMP_WAIT_POLICY=PASSIVE;LC_ALL=C;CUTBENCH_ROOT=${PROJECT_SOURCE_DIR}")
    endif()
  endforeach()
endforeach()

# Every counted check can fail: the audit over the case files, the quick-tier records just written
# (each carries its perturbation audit) and the paper-resolution records.
add_test(NAME check_audit COMMAND cutbench audit --results ${CMAKE_BINARY_DIR}/results-quick)
set_tests_properties(check_audit PROPERTIES LABELS "quick" FIXTURES_REQUIRED results_quick
  ENVIRONMENT "LC_ALL=C;CUTBENCH_ROOT=${PROJECT_SOURCE_DIR}")
