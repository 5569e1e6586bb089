#!/usr/bin/env bash
# The tests: install packages, build (release, warnings as errors), run unit + verification +
# quick-tier cases with ctest (JUnit in build/release/junit/), then the unit tests under ASan+UBSan,
# then the libFuzzer harnesses of the input readers (about a minute).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup-debian.sh
start=$(date +%s)
cmake --preset release >/dev/null
cmake --build --preset release
ctest --preset quick --output-junit junit/ctest-quick.xml
cmake --preset sanitize >/dev/null
cmake --build --preset sanitize
ctest --preset sanitize --output-junit junit/ctest-sanitize.xml
bash scripts/fuzz.sh
echo "tests: done in $(( $(date +%s) - start )) s"
