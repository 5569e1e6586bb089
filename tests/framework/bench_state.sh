#!/usr/bin/env bash
# cutbench bench SOLVER ... --state FILE: the first call stops at a checkpoint and leaves FILE, the
# second resumes from it and times only the rest; the resumed run's results equal those of an
# uninterrupted run; a state of other parameters and a non-positive --state-minutes are bad input.
set -u
cutbench="$1"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail=0
params=("speed=318.5 m/min" "t1=0.1 mm" particles_over_height=9 "length=1 mm" "cut_distance=0.3 mm")
scalars() { /usr/bin/python3 -c 'import json,sys; r=json.load(open(sys.argv[1]))["runs"][0]; print(json.dumps(r["scalars"], sort_keys=True))' "$1"; }

out=$("$cutbench" bench sph "${params[@]}" --state "$work/s.state" --state-minutes 0.003 -j 1 --out "$work/a" 2>/dev/null)
if [[ $? -ne 0 || "$out" != *"state written to"* || ! -s "$work/s.state" ]]; then echo "FAIL write: $out"; fail=1; else echo "ok   write: $out"; fi

out=$("$cutbench" bench sph "${params[@]}" --state "$work/s.state" -j 1 --out "$work/b" 2>/dev/null)
rc=$?
timed=$(/usr/bin/python3 -c 'import json,sys; r=json.load(open(sys.argv[1]))["runs"][0]; print(int(r["steps_timed"]), int(r["scalars"]["steps"]), r["particle_steps_per_s"] > 0)' "$work/b/bench/sph.json" 2>&1)
read -r t total positive <<<"$timed"
if [[ $rc -ne 0 || "$positive" != "True" || $t -le 0 || $t -ge $total ]]; then echo "FAIL resume: rc $rc, $timed, $out"; fail=1
else echo "ok   resume: $t of $total steps timed"; fi

"$cutbench" bench sph "${params[@]}" -j 1 --out "$work/c" >/dev/null 2>&1
if [[ "$(scalars "$work/b/bench/sph.json")" != "$(scalars "$work/c/bench/sph.json")" ]]; then echo "FAIL resumed results differ from an uninterrupted run"; fail=1
else echo "ok   resumed results equal an uninterrupted run"; fi

msg=$("$cutbench" bench sph "${params[@]}" mu=0.5 --state "$work/s.state" -j 1 --out "$work/d" 2>&1 >/dev/null); rc=$?
if [[ $rc -ne 2 || "$msg" != *"--state"* || -e "$work/d" ]]; then echo "FAIL other parameters: exit $rc: $msg"; fail=1; else echo "ok   other parameters: $msg"; fi
msg=$("$cutbench" bench sph "${params[@]}" --state "$work/t.state" --state-minutes 0 -j 1 --out "$work/e" 2>&1 >/dev/null); rc=$?
if [[ $rc -ne 2 || "$msg" != *"--state-minutes"* || -e "$work/t.state" ]]; then echo "FAIL minutes: exit $rc: $msg"; fail=1; else echo "ok   minutes: $msg"; fi
exit $fail
