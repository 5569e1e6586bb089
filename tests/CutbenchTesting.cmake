# cutbench_add_boost_test(NAME SOURCES ... LIBS ... LABELS ...)
# One Boost.Test executable; every test runs with pinned threads, C locale, no colour, and writes
# a JUnit report to ${CMAKE_BINARY_DIR}/junit/<name>.xml.
function(cutbench_add_boost_test name)
  cmake_parse_arguments(ARG "" "" "SOURCES;LIBS;LABELS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_compile_definitions(${name} PRIVATE BOOST_TEST_DYN_LINK
                             CUTBENCH_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
  target_link_libraries(${name} PRIVATE ${ARG_LIBS} Boost::unit_test_framework
                        cutbench::warnings cutbench::sanitize)
  file(MAKE_DIRECTORY ${CMAKE_BINARY_DIR}/junit)
  add_test(NAME ${name}
           COMMAND ${name} --log_level=test_suite --report_level=short
                   --logger=HRF,test_suite --logger=JUNIT,all,${CMAKE_BINARY_DIR}/junit/${name}.xml)
  set_tests_properties(${name} PROPERTIES
    LABELS "${ARG_LABELS}"
    ENVIRONMENT "OMP_NUM_THREADS=${CUTBENCH_TEST_THREADS};OMP_WAIT_POLICY=PASSIVE;LC_ALL=C;BOOST_TEST_COLOR_OUTPUT=no")
endfunction()
