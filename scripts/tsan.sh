#!/usr/bin/env bash
# ThreadSanitizer over the OpenMP kernels: builds everything with Clang 14 and -fsanitize=thread
# (the `tsan` preset; LLVM's libomp), then runs the test programs of the four solvers with two
# OpenMP threads and LLVM's Archer tool (OMP_TOOL_LIBRARIES=libarcher.so), which tells TSan about
# OpenMP's barriers, reductions and locks; halt_on_error: the first data race fails the run.
# About 25 minutes to build and 7 to test on 2 cores, so it is not part of scripts/test.sh (CI).
#   bash scripts/tsan.sh
set -euo pipefail
cd "$(dirname "$0")/.."
test -f /usr/lib/llvm-14/lib/libarcher.so || { echo "tsan.sh: needs libomp-14-dev (scripts/setup-debian.sh)"; exit 2; }
cmake --preset tsan >/dev/null
cmake --build --preset tsan
ctest --preset tsan --output-junit junit/ctest-tsan.xml
