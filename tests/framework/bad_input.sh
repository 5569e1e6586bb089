#!/usr/bin/env bash
# Bad input must exit with code 2, print one message naming the field, and write nothing.
set -u
cutbench="$1"; root="$2"
fail=0
expect() {  # expect <description> <field substring> <args...>
  local what="$1" field="$2"; shift 2
  local out; out=$(mktemp -d)
  local msg; msg=$("$cutbench" "$@" --out "$out/results" 2>&1 >/dev/null); local rc=$?
  if [[ $rc -ne 2 ]]; then echo "FAIL $what: exit $rc (expected 2): $msg"; fail=1;
  elif [[ "$msg" != *"$field"* ]]; then echo "FAIL $what: message does not name '$field': $msg"; fail=1;
  elif [[ -n "$(ls -A "$out")" ]]; then echo "FAIL $what: wrote files: $(ls -R "$out")"; fail=1;
  else echo "ok   $what: $msg"; fi
  rm -rf "$out"
}
expect_eval() {  # model evaluation with bad parameters
  local what="$1" field="$2"; shift 2
  local msg; msg=$("$cutbench" eval "$@" 2>&1 >/dev/null); local rc=$?
  if [[ $rc -ne 2 ]]; then echo "FAIL $what: exit $rc (expected 2): $msg"; fail=1;
  elif [[ "$msg" != *"$field"* ]]; then echo "FAIL $what: message does not name '$field': $msg"; fail=1;
  else echo "ok   $what: $msg"; fi
}
expect_cmd() {  # any other subcommand: exit 2 and a message naming the field
  local what="$1" field="$2"; shift 2
  local msg; msg=$("$cutbench" "$@" 2>&1 >/dev/null); local rc=$?
  if [[ $rc -ne 2 ]]; then echo "FAIL $what: exit $rc (expected 2): $msg"; fail=1;
  elif [[ "$msg" != *"$field"* ]]; then echo "FAIL $what: message does not name '$field': $msg"; fail=1;
  else echo "ok   $what: $msg"; fi
}
bad="$root/tests/data/bad_cases"
expect "unknown key"          "colour"           run "$bad/nairn2015/unknown_key.toml"
expect "wrong unit"           "params.t1"         run "$bad/nairn2015/wrong_unit.toml"
expect "negative modulus"     "E_prime"          run "$bad/nairn2015/negative_modulus.toml"
expect "rake >= 90 deg"       "rake"             run "$bad/nairn2015/rake_90.toml"
expect "negative friction"    "mu"               run "$bad/nairn2015/negative_mu.toml"
expect "missing reference"    "reference.file"   run "$bad/nairn2015/missing_reference.toml"
expect "known_failure as a plain string" "known_failure" run "$bad/nairn2015/known_failure_plain.toml"
expect "known_failure without finding"  "finding"       run "$bad/nairn2015/known_failure_no_finding.toml"
expect "finding not in FINDINGS.md"     "finding"       run "$bad/nairn2015/finding_unknown.toml"
expect "known_failure text too long"    "known_failure.quick" run "$bad/nairn2015/known_failure_long.toml"
expect "no tolerance_source"            "tolerance_source" run "$bad/nairn2015/no_tolerance_source.toml"
expect "unknown check kind"             "kind"          run "$bad/nairn2015/unknown_kind.toml"
expect "scatter without its source"     "scatter_source" run "$bad/nairn2015/scatter_without_source.toml"
if "$cutbench" runs "$root/reports/full_tier/runs" --case nairn2015/fig04 --tier quick >/dev/null 2>&1; then
  expect "MPM cfl beyond stability"     "cfl"           run "$bad/nairn2015/mpm_cfl_unstable.toml"
fi
expect "unknown case"         "case"             run nairn2015/fig99
expect "unknown paper"        "--paper"          run --paper nobody2020
expect_eval "eval unknown param"  "colour"  atkins_touching colour=3
expect_eval "eval rake 90"        "rake"    atkins_touching G_c=2000 sigma_y=25MPa t1=1mm rake=90deg
expect_eval "eval negative mu"    "mu"      atkins_touching G_c=2000 sigma_y=25MPa t1=1mm rake=30deg mu=-0.1
expect_eval "eval wrong unit"     "t1: wrong unit" atkins_touching G_c=2000 sigma_y=25MPa t1=1MPa rake=30deg
expect "run cache not writable"  "--run-cache"  run afrasiabi2021/fig03 --run-cache /proc/cutbench-no-such-dir
expect "checkpoints without a run store" "--checkpoint-minutes" run aghababaei2021/fig04 --checkpoint-minutes 5
expect "checkpoint interval negative"    "--checkpoint-minutes" run aghababaei2021/fig04 --checkpoint-minutes -1
expect_cmd "runs: no directory"         "runs"       runs /proc/cutbench-no-such-dir
expect_cmd "runs --compute without cases" "--compute" runs /tmp --compute
expect_cmd "runs: bad tier"            "--tier"     runs --case afrasiabi2021/fig06 --tier medium
expect_cmd "runs: bad tier, every case" "--tier"    runs /tmp --tier medium --compute
# `--tier full` alone plans every case of the tier: the dry-run array covers every paper's cases
plan=$("$cutbench" runs "$root/reports/full_tier/runs" --tier full --compute --slurm --dry-run --partition p 2>&1); rc=$?
if [[ $rc -ne 0 || "$plan" != *"--case 'afrasiabi2021/fig02'"* || "$plan" != *"--case 'nairn2015/fig17'"* ||
      "$plan" != *"--case 'kahwash2018/table6'"* || "$plan" != *"#SBATCH --array=0-"* ]]; then
  echo "FAIL runs --tier full: the dry run does not plan every case (exit $rc)"; fail=1
else echo "ok   runs --tier full --compute --slurm --dry-run plans every case"; fi
expect_cmd "runs --compute: unwritable" "--run-cache" runs /proc/cutbench-no-such-dir --case afrasiabi2021/fig03 --compute
if [[ "$("$cutbench" bench efg_cutting completion_guard=1.4 2>&1 >/dev/null)" == *"unknown benchmark"* ]]; then
  echo "skip option not a whole number: the EFG solver is not in this build (CUTBENCH_SOLVERS=OFF)"
else
  expect_cmd "option not a whole number" "completion_guard" bench efg_cutting completion_guard=1.4
fi
# Typed parameters: integers are whole numbers, switches true/false, options one of their names;
# all refused at load, before anything runs.
typed=$(mktemp -d)
typed_case() {  # typed_case <paper> <name> <solver> <model> <params inline table> [extra series lines]
  mkdir -p "$typed/$1"
  printf 'id = "%s/%s"\npaper = "%s"\nitem = "Bad"\ntitle = "bad input"\nrequirement = "must be rejected"\nstatus = "implemented"\nsolver = "%s"\nmodels = ["%s"]\ntiers = ["quick"]\n\n[[series]]\nname = "s"\nmodel = "%s"\nparams = %s\n%s\n' \
    "$1" "$2" "$1" "$3" "$4" "$4" "$5" "${6:-}" > "$typed/$1/$2.toml"
  echo "$typed/$1/$2.toml"
}
if "$cutbench" describe mpm_cutting >/dev/null 2>&1; then
  expect "integer given a fraction"    "snapshots"        run "$(typed_case nairn2015 snap mpm mpm_cutting '{ snapshots = 1.5 }')"
  expect "order given a fraction"      "position_order"   run "$(typed_case nairn2015 order mpm mpm_cutting '{ position_order = 1.5 }')"
  expect "option given its old code"   "strain_update"    run "$(typed_case nairn2015 code mpm mpm_cutting '{ strain_update = 1 }')"
  expect "option given an unknown name" "strain_update"   run "$(typed_case nairn2015 name mpm mpm_cutting '{ strain_update = "usf" }')"
  expect "switch given a fraction"     "musl_recontact"   run "$(typed_case nairn2015 sw mpm mpm_cutting '{ musl_recontact = 0.5 }')"
  expect "switch given a string"       "musl_recontact"   run "$(typed_case nairn2015 sws mpm mpm_cutting '{ musl_recontact = "yes" }')"
  expect "count given as a string"     "particles_through_chip" run "$(typed_case nairn2015 cnt mpm mpm_cutting '{ particles_through_chip = "4.5" }')"
  expect "option swept by from/to"     "sweep"            run "$(typed_case nairn2015 swp mpm mpm_cutting '{ t1 = "1 mm" }' 'sweep = { param = "contact_detection", from = 0, to = 2, n = 3 }')"
  expect "option swept by a bad name"  "sweep.values"     run "$(typed_case nairn2015 swv mpm mpm_cutting '{ t1 = "1 mm" }' 'sweep = { param = "contact_detection", values = ["nodal_gap", "touching"] }')"
  expect "switch given a number (SPH)" "enhanced_thermal" run "$(typed_case afrasiabi2021 sph sph sph_cutting '{ enhanced_thermal = 0.5 }')"
  expect "option given a number (limit)" "steady_state"   run "$(typed_case figueiredo2024 lim limit limit_cutting '{ steady_state = 2 }')"
  expect "option given a number (EFG)" "criterion"        run "$(typed_case kahwash2018 efg efg efg_cutting '{ criterion = 2 }')"
  # selectors name only declared outputs and tables (see `cutbench describe SOLVER`)
  check_with() { printf '[[checks]]\nkey = "k"\nkind = "verification"\nmetric = "relative"\nunits = "N/m"\nsource = "test"\nreference = 1.0\ntolerance = 0.1\n%s\n' "$1"; }
  expect "check of an undeclared output" "value.output" run "$(typed_case nairn2015 out mpm mpm_cutting '{ t1 = "1 mm" }' "$(check_with 'value = { series = "s", output = "F_cut" }')")"
  expect "check of an undeclared table" "value.table" run "$(typed_case nairn2015 tab mpm mpm_cutting '{ t1 = "1 mm" }' "$(check_with 'value = { series = "s", run = 0, table = "force", output = "F_c", row = -1 }')")"
  expect "check of an undeclared column" "value.x" run "$(typed_case nairn2015 col mpm mpm_cutting '{ t1 = "1 mm" }' "$(check_with 'value = { series = "s", run = 0, table = "forces", output = "F_c", x = "time", at = 0.001 }')")"
  expect "check of a series not in the case" "value.series" run "$(typed_case nairn2015 ser mpm mpm_cutting '{ t1 = "1 mm" }' "$(check_with 'value = { series = "mpm", output = "F_c" }')")"
  expect "plot line of an undeclared column" "lines[0].y" run "$(typed_case nairn2015 plt mpm mpm_cutting '{ t1 = "1 mm" }' "$(printf '%s' '[[plots]]
name = "p"
[[plots.lines]]
series = "s"
run = 0
table = "forces"
x = "t"
y = "Fc"')")"
  expect_cmd "describe an unknown solver" "name" describe mpm_cuting
  expect "a retired name of a shared quantity" "glossary name" run "$(typed_case nairn2015 gl mpm mpm_cutting '{ h = "1 mm" }')"
  # resources: a run's footprint is estimated at load and refused above --max-memory (default 8 GiB)
  expect "MPM run of 3e7 particles" "GiB" run "$(typed_case nairn2015 big mpm mpm_cutting '{ particles_through_chip = 200, width_factor = 200 }')"
  expect "SPH run of 1.6e11 particles" "GiB" run "$(typed_case afrasiabi2021 big sph sph_cutting '{ particles_over_height = 400, length = "1 m", height = "1 um", t1 = "0.1 um", cut_distance = "1 mm" }')"
  expect "EFG run of 1e10 nodes" "GiB" run "$(typed_case kahwash2018 big efg efg_cutting '{ spacing = "0.01 um", t1 = "0.025 um", work_length = "1.5 mm", work_height = "0.75 mm", notch = "0.25 mm" }')"
  expect "max memory not positive" "--max-memory" run aghababaei2021/fig04 --max-memory 0
  expect_eval "eval option by an unknown name" "criterion" failure_envelope criterion=tsai plane=s11_s22
  expect_eval "eval option by its old code"    "plane"     failure_envelope criterion=hashin plane=0
else
  echo "skip typed solver parameters: no solvers in this build (CUTBENCH_SOLVERS=OFF)"
fi
expect "analytic option by its old code" "criterion" run "$(typed_case kahwash2018 env analytic failure_envelope '{ criterion = 0, plane = "s11_s22" }')"
rm -rf "$typed"

# Resource exhaustion: nesting and size are refused before the file is parsed.
gen=$(mktemp -d); mkdir -p "$gen/nairn2015"
{ echo 'id = "nairn2015/deep_header"'; printf '['; for i in $(seq 1 2000); do printf 'a.'; done; echo 'b]'; } > "$gen/nairn2015/deep_header.toml"
{ echo 'id = "nairn2015/deep_inline"'; printf 'x = '; for i in $(seq 1 500); do printf '{a = '; done; printf '1'; for i in $(seq 1 500); do printf '}'; done; echo; } > "$gen/nairn2015/deep_inline.toml"
head -c 2000000 /dev/zero | tr '\0' '#' > "$gen/nairn2015/huge.toml"
expect "dotted header 2000 deep"  "nested"  run "$gen/nairn2015/deep_header.toml"
expect "inline tables 500 deep"   "nested"  run "$gen/nairn2015/deep_inline.toml"
expect "2 MB case file"           "bytes"   run "$gen/nairn2015/huge.toml"
rm -rf "$gen"

# Temporaries left by killed runs (no such process) are removed at the next run; others are kept.
left=$(mktemp -d); mkdir -p "$left/aghababaei2021"
touch "$left/aghababaei2021/fig04.h5.tmp.999999999" "$left/aghababaei2021/fig04.run.999999998.2.tmp" \
      "$left/aghababaei2021/fig04.json.tmp.1"
"$cutbench" run aghababaei2021/fig04 --out "$left" >/dev/null 2>&1
if [[ -e "$left/aghababaei2021/fig04.h5.tmp.999999999" || -e "$left/aghababaei2021/fig04.run.999999998.2.tmp" ||
      ! -e "$left/aghababaei2021/fig04.json.tmp.1" ]]; then echo "FAIL stale temporaries: $(ls "$left/aghababaei2021")"; fail=1;
else echo "ok   temporaries of dead writers removed, of live ones kept"; fi
rm -rf "$left"

# A stored run with a flipped bit is reported as damaged, never read back as current.
store=$(mktemp -d)
cp "$root"/reports/full_tier/runs/sph_laplacian-*.run "$store"/
f=$(ls "$store"/*.run | head -n 1)
printf '\xff' | dd of="$f" bs=1 seek=$(( $(stat -c %s "$f") / 2 )) conv=notrunc status=none
msg=$("$cutbench" runs "$store" --check 2>&1); rc=$?
if [[ $rc -ne 1 || "$msg" != *"damaged: checksum mismatch"* ]]; then echo "FAIL flipped bit: exit $rc: $msg"; fail=1;
else echo "ok   flipped bit in a stored run: reported damaged"; fi
rm -rf "$store"

# The report generator is started without a shell: a path is never interpreted.
work=$(mktemp -d)
( cd "$work" && "$cutbench" report --results 'x$(touch PWNED)' --out r >/dev/null 2>&1 )
if [[ -e "$work/PWNED" ]]; then echo "FAIL shell injection through report --results"; fail=1;
else echo "ok   report paths are not interpreted by a shell"; fi
rm -rf "$work"

# A run that faults is an ERROR: exit 3, the series and the reason named (results are written).
if "$cutbench" runs "$root/reports/full_tier/runs" --case nairn2015/fig04 --tier quick >/dev/null 2>&1; then
  out=$(mktemp -d)
  msg=$("$cutbench" run "$root/tests/data/fault_cases/nairn2015/total_time_overflow.toml" --out "$out" 2>&1); rc=$?
  if [[ $rc -ne 3 ]]; then echo "FAIL fault: exit $rc (expected 3): $msg"; fail=1;
  elif [[ "$msg" != *"ERROR"*"total_time"* ]]; then echo "FAIL fault: no ERROR naming total_time: $msg"; fail=1;
  elif ! grep -q '"status": "ERROR"' "$out/nairn2015/total_time_overflow.json"; then echo "FAIL fault: record is not ERROR"; fail=1;
  else echo "ok   fault is ERROR, exit 3"; fi
  rm -rf "$out"
else
  echo "skip fault: the MPM solver is not in this build (CUTBENCH_SOLVERS=OFF)"
fi
exit $fail
