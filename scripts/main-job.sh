#!/usr/bin/env bash
# The main job: install packages, build (release), run the quick tier, write the HTML report.
#   results/  HDF5 + checks.json      report/index.html  the report
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup-debian.sh
cmake --preset release >/dev/null
cmake --build --preset release
export OMP_NUM_THREADS="${OMP_NUM_THREADS:-2}" OMP_WAIT_POLICY=PASSIVE LC_ALL=C
rc=0
./build/release/benchmarks/cli/cutbench run --tier quick --out results || rc=$?
./build/release/benchmarks/cli/cutbench report --results results --out report
./build/release/benchmarks/cli/cutbench list --results results
echo "main job: report at $(pwd)/report/index.html (run exit code $rc)"
exit "$rc"
