# cutbench::warnings — warning flags for project code (never for third-party headers).
add_library(cutbench_warnings INTERFACE)
add_library(cutbench::warnings ALIAS cutbench_warnings)
target_compile_options(cutbench_warnings INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Wcast-align
  -Wunused -Woverloaded-virtual -Wdouble-promotion -Wformat=2)
if(CUTBENCH_WARNINGS_AS_ERRORS)
  target_compile_options(cutbench_warnings INTERFACE -Werror)
endif()

# cutbench::sanitize — ASan + UBSan when CUTBENCH_SANITIZE is on.
add_library(cutbench_sanitize INTERFACE)
add_library(cutbench::sanitize ALIAS cutbench_sanitize)
if(CUTBENCH_FUZZ)  # every library instrumented for coverage; the harnesses link libFuzzer
  target_compile_options(cutbench_sanitize INTERFACE
    -fsanitize=fuzzer-no-link,address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  target_link_options(cutbench_sanitize INTERFACE -fsanitize=address,undefined)
elseif(CUTBENCH_TSAN)  # OpenMP synchronisation is made visible to TSan by LLVM's Archer (OMP_TOOL_LIBRARIES)
  target_compile_options(cutbench_sanitize INTERFACE -fsanitize=thread -fno-omit-frame-pointer)
  target_link_options(cutbench_sanitize INTERFACE -fsanitize=thread)
elseif(CUTBENCH_SANITIZE)  # float-cast-overflow is not part of GCC's `undefined`
  target_compile_options(cutbench_sanitize INTERFACE
    -fsanitize=address,undefined,float-cast-overflow -fno-omit-frame-pointer -fno-sanitize-recover=all)
  target_link_options(cutbench_sanitize INTERFACE -fsanitize=address,undefined,float-cast-overflow)
endif()

# Helper: one library target per component with a namespaced alias.
function(cutbench_add_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS" ${ARGN})
  add_library(cutbench_${name} ${ARG_SOURCES})
  add_library(cutbench::${name} ALIAS cutbench_${name})
  target_include_directories(cutbench_${name} PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/include)
  target_link_libraries(cutbench_${name} PUBLIC ${ARG_PUBLIC_DEPS} cutbench::sanitize
                        PRIVATE ${ARG_PRIVATE_DEPS} cutbench::warnings)
endfunction()
