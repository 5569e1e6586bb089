# cutbench_add_boost_test(NAME SOURCES ... LIBS ... LABELS ... [SPLIT suite...])
# One Boost.Test executable; every test runs with pinned threads, C locale, no colour, and writes
# a JUnit report to ${CMAKE_BINARY_DIR}/junit/<name>.xml (<name>.<suite>.xml for a SPLIT suite).
function(cutbench_add_boost_test name)
  # SPLIT: test suites registered as ctest tests of their own (`<name>:<suite>`), so that ctest runs
  # the long suites of one executable side by side; `<name>` runs the remaining suites.
  cmake_parse_arguments(ARG "" "" "SOURCES;LIBS;LABELS;SPLIT" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_compile_definitions(${name} PRIVATE BOOST_TEST_DYN_LINK
                             CUTBENCH_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
  target_link_libraries(${name} PRIVATE ${ARG_LIBS} Boost::unit_test_framework
                        cutbench::warnings cutbench::sanitize)
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR}/tests)
  if(CUTBENCH_SANITIZE OR CUTBENCH_TSAN)  # release_only.hpp: the long repeats run in the release suite
    target_compile_definitions(${name} PRIVATE CUTBENCH_SANITIZED_BUILD)
  endif()
  file(MAKE_DIRECTORY ${CMAKE_BINARY_DIR}/junit)
  set(logs --log_level=test_suite --report_level=short --logger=HRF,test_suite)
  set(rest "")
  set(tests ${name})
  foreach(suite IN LISTS ARG_SPLIT)
    list(APPEND rest "--run_test=!${suite}")
    list(APPEND tests ${name}:${suite})
    add_test(NAME ${name}:${suite}
             COMMAND ${name} --run_test=${suite} ${logs} --logger=JUNIT,all,${CMAKE_BINARY_DIR}/junit/${name}.${suite}.xml)
  endforeach()
  add_test(NAME ${name}
           COMMAND ${name} ${rest} ${logs} --logger=JUNIT,all,${CMAKE_BINARY_DIR}/junit/${name}.xml)
  set_tests_properties(${tests} PROPERTIES
    LABELS "${ARG_LABELS}"
    ENVIRONMENT "OMP_NUM_THREADS=${CUTBENCH_TEST_THREADS};OMP_WAIT_POLICY=PASSIVE;LC_ALL=C;BOOST_TEST_COLOR_OUTPUT=no")
endfunction()
