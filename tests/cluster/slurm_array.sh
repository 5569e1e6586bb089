#!/usr/bin/env bash
# The paper-resolution tier through a real Slurm (ctest label `cluster`): install Debian's
# slurm-wlm and munge when missing (root), start munged, slurmctld and slurmd on this machine with
# a single-node configuration in a scratch directory, submit a small case's runs as a job array
# (`cutbench runs --compute --slurm`), wait, and check that the store holds the runs a local
# `--compute` makes (same files, same results to the last bit) and that the dependent job
# recorded the case. The daemons are stopped and the scratch directory removed in every case.
# Exit 77 (ctest: skipped, never passed) where Slurm cannot be installed or started here, saying why.
#   tests/cluster/slurm_array.sh CUTBENCH REPO_ROOT
set -uo pipefail
cutbench="$1"
root="$2"
case_id="afrasiabi2021/fig03"  # full tier: three Laplacian reconstructions, seconds each
skip() { echo "SKIP: $*"; exit 77; }
fail() { echo "FAIL: $*"; exit 1; }

if ! command -v slurmctld >/dev/null || ! command -v slurmd >/dev/null || ! command -v munged >/dev/null; then
  [[ $(id -u) -eq 0 ]] && command -v apt-get >/dev/null || skip "slurm-wlm and munge are not installed and this user cannot install them"
  echo "installing slurm-wlm and munge"
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq slurm-wlm munge >/dev/null 2>&1 ||
    { DEBIAN_FRONTEND=noninteractive apt-get update -qq >/dev/null 2>&1 &&
      DEBIAN_FRONTEND=noninteractive apt-get install -y -qq slurm-wlm munge >/dev/null 2>&1; } ||
    skip "apt-get could not install slurm-wlm and munge"
fi
[[ $(id -u) -eq 0 ]] || skip "slurmd needs root here (it runs the jobs as their user)"

work=$(mktemp -d /tmp/cutbench-slurm.XXXXXX)
stop() {
  for f in "$work/slurmd.pid" "$work/slurmctld.pid" "$work/munge/munged.pid"; do
    [[ -f "$f" ]] && kill "$(cat "$f")" 2>/dev/null
  done
  sleep 1
  for f in "$work/slurmd.pid" "$work/slurmctld.pid" "$work/munge/munged.pid"; do
    [[ -f "$f" ]] && kill -9 "$(cat "$f")" 2>/dev/null
  done
  rm -rf "$work"
}
trap stop EXIT
mkdir -p "$work"/{spool,state,log,munge,local,store,records}
dd if=/dev/urandom of="$work/munge/munge.key" bs=1024 count=1 2>/dev/null
chmod 400 "$work/munge/munge.key"
sock="$work/munge/munge.sock"
munged --key-file="$work/munge/munge.key" --socket="$sock" --pid-file="$work/munge/munged.pid" \
  --log-file="$work/munge/munged.log" --seed-file="$work/munge/seed" -f ||
  skip "munged did not start: $(tail -n 3 "$work/munge/munged.log" 2>/dev/null)"
host=$(hostname)
port=$((20000 + RANDOM % 20000))
cat >"$work/slurm.conf" <<CONF
ClusterName=cutbench
SlurmctldHost=$host
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$sock
CredType=cred/munge
MpiDefault=none
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
SlurmctldPort=$port
SlurmdPort=$((port + 1))
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/log/slurmctld.log
SlurmdLogFile=$work/log/slurmd.log
JobCompType=jobcomp/none
AccountingStorageType=accounting_storage/none
NodeName=$host CPUs=$(nproc) State=UNKNOWN
PartitionName=debug Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF="$work/slurm.conf"
slurmctld -f "$SLURM_CONF" || skip "slurmctld did not start: $(tail -n 3 "$work/log/slurmctld.log" 2>/dev/null)"
slurmd -f "$SLURM_CONF" || skip "slurmd did not start: $(tail -n 3 "$work/log/slurmd.log" 2>/dev/null)"
for _ in $(seq 30); do
  sinfo -h -o %t 2>/dev/null | grep -qx idle && break
  sleep 1
done
sinfo -h -o %t 2>/dev/null | grep -qx idle ||
  skip "the Slurm node did not come up: $(tail -n 3 "$work/log/slurmd.log" 2>/dev/null)"

cd "$root" || fail "no repository at $root"
"$cutbench" runs "$work/local" --case "$case_id" --compute -j 1 >"$work/log/local.txt" 2>&1 ||
  fail "local --compute: $(tail -n 3 "$work/log/local.txt")"
"$cutbench" runs "$work/store" --case "$case_id" --compute --slurm --job-name cbtest --records "$work/records" \
  >"$work/log/submit.txt" 2>&1 || fail "submission: $(cat "$work/log/submit.txt")"
grep -q "submitted array job" "$work/log/submit.txt" || fail "no submission: $(cat "$work/log/submit.txt")"
for _ in $(seq 120); do
  [[ -z $(squeue -h 2>/dev/null) ]] && break
  sleep 1
done
[[ -z $(squeue -h 2>/dev/null) ]] || fail "jobs still queued after 120 s: $(squeue)"

# the same runs, the same results (run files carry provenance notes, so results are compared)
results() { "$cutbench" runs "$1" --json --results | /usr/bin/python3 -c '
import json, sys
for r in sorted(json.load(sys.stdin), key=lambda r: r["file"]):
    if r["kind"] == "run":
        print(r["file"], r["state"], json.dumps(r["scalars"], sort_keys=True))'; }
results "$work/local" >"$work/log/local.runs"
results "$work/store" >"$work/log/store.runs"
[[ -s "$work/log/local.runs" ]] || fail "the local store holds no run"
diff "$work/log/local.runs" "$work/log/store.runs" >/dev/null ||
  fail "the Slurm store differs from the local one: $(diff "$work/log/local.runs" "$work/log/store.runs" | head -5); array logs: $(cat "$work"/store/slurm/*.out 2>/dev/null | tail -n 5)"
record="$work/records/${case_id}.json"
[[ -f "$record" ]] || fail "the record job wrote no $record: $(cat "$work"/store/slurm/cbtest-record-*.out 2>/dev/null | tail -n 5)"
grep -q '"tier": "full"' "$record" || fail "the record is not a full-tier one"
echo "PASS: $(wc -l <"$work/log/store.runs") runs computed by a Slurm job array equal the local ones; $case_id recorded by the dependent job"
