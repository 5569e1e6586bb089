#!/usr/bin/env bash
# The main job: install packages, build (release), run the quick tier, write the HTML report.
#   results/  HDF5 + checks.json      report/index.html  the report
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup-debian.sh
cmake --preset release >/dev/null
cmake --build --preset release
export OMP_WAIT_POLICY=PASSIVE LC_ALL=C
# independent cases side by side, one process per core, one thread each (the quick tier's runs are
# too small for a second thread to pay)
jobs="${CUTBENCH_JOBS:-$(nproc)}"
rc=0
./build/release/benchmarks/cli/cutbench run --tier quick --jobs "$jobs" -j 1 --out results || rc=$?
./build/release/benchmarks/cli/cutbench report --results results --out report
./build/release/benchmarks/cli/cutbench list --results results
echo "main job: report at $(pwd)/report/index.html (run exit code $rc)"
exit "$rc"
