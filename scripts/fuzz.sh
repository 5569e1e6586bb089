#!/usr/bin/env bash
# Fuzz the readers of untrusted input with libFuzzer (Clang, ASan + UBSan):
#   fuzz_case       case files (TOML)          seeds: every case file and the bad-input cases
#   fuzz_quantity   "value unit" quantities     seeds: tests/fuzz/seeds/quantity
#   fuzz_reference  reference CSV tables        seeds: every reference table
#   fuzz_run_file   stored runs, checkpoints    seeds: the small stored runs
# Each harness first replays its regression inputs (tests/fuzz/regressions/<target>/: inputs that
# once crashed, kept), then fuzzes for SECONDS (default 12; CI runs the default, about a minute in
# all). A crash leaves its input in build/fuzz/crashes/ and fails the script.
#   bash scripts/fuzz.sh [SECONDS]
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-12}"
cmake --preset fuzz >/dev/null
cmake --build --preset fuzz
bin=build/fuzz/tests/fuzz
work=build/fuzz/corpus
mkdir -p build/fuzz/crashes
rm -rf "$work"
mkdir -p "$work"/{case,quantity,reference,run_file}
for f in benchmarks/*/*.toml; do cp "$f" "$work/case/$(basename "$(dirname "$f")")_$(basename "$f")"; done
for f in tests/data/bad_cases/*/*.toml; do cp "$f" "$work/case/bad_$(basename "$f")"; done
cp tests/fuzz/seeds/quantity/* "$work/quantity/"
for f in reference_data/*/*.csv; do cp "$f" "$work/reference/$(basename "$(dirname "$f")")_$(basename "$f")"; done
find reports/full_tier/runs -name '*.run' -size -64k -exec cp {} "$work/run_file/" \;
export CUTBENCH_ROOT="$PWD" ASAN_OPTIONS="detect_leaks=0:allocator_may_return_null=1" UBSAN_OPTIONS="halt_on_error=1"
status=0
for t in case quantity reference run_file; do
  regressions=(tests/fuzz/regressions/$t/*)
  if [[ -e "${regressions[0]}" ]]; then
    "$bin/fuzz_$t" "${regressions[@]}" >/dev/null 2>&1 || { echo "fuzz_$t: a regression input crashes again"; status=1; }
  fi
  if "$bin/fuzz_$t" "$work/$t" -seed=1 -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 \
       -artifact_prefix="build/fuzz/crashes/$t-" >"build/fuzz/$t.log" 2>&1; then
    echo "fuzz_$t: $(grep -Eo 'Done [0-9]+ runs in [0-9]+ second' "build/fuzz/$t.log" | tail -n 1), no crash"
  else
    echo "fuzz_$t: CRASH (build/fuzz/$t.log, input in build/fuzz/crashes/)"; tail -n 30 "build/fuzz/$t.log"; status=1
  fi
done
exit $status
