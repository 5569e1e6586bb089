#!/usr/bin/env bash
# Fill reports/full_tier/runs with the full-tier solver runs of one method, cheap runs first, one
# thread each (two campaigns side by side use the two cores without oversubscribing them). Runs
# already stored are skipped and a run with a checkpoint there resumes, so the script can be
# started again on any machine after an interruption.
#   scripts/full-tier-campaign.sh sph|efg|mpm [cutbench executable]   (CUTBENCH_ROOT: the checkout, when run from a copy)
# Needs a release build. Afterwards: `cutbench runs` (what is stored), record the cases whose runs
# are complete (reports/full_tier/runs/README.md), commit the new .run files; before a machine
# goes away, `git add -f` the checkpoints of unfinished runs.
# To leave the machine to other work (a build, CI), start it in a session of its own:
#   setsid nohup nice -n 15 bash scripts/full-tier-campaign.sh mpm > campaign.log 2>&1 &
# Linux schedules sessions (autogroups) against each other before nice counts, so a niced campaign
# in its own session still takes half of the CPU from a build in another one; the script therefore
# lowers its session's weight too (only when it leads that session, so never a terminal's).
set -uo pipefail
if [ "$(cut -d' ' -f6 /proc/$$/stat 2>/dev/null)" = "$$" ] && [ -w /proc/self/autogroup ]; then  # field 6: the session
  echo 19 > /proc/self/autogroup || true
fi
cd "${CUTBENCH_ROOT:-$(dirname "$0")/..}"
method="${1:-}"
cutbench="${2:-build/release/benchmarks/cli/cutbench}"
store=reports/full_tier/runs
failed=0
compute() {  # a failed run is reported and the campaign goes on
  "$cutbench" runs "$store" --compute --skip-running -j 1 --checkpoint-minutes "${CHECKPOINT_MINUTES:-5}" "$@" || failed=1
}
case "$method" in
  sph)
    # Most cases per CPU-hour first: the enhanced mu = 0.35 run (Fig 2 alone needs it) and the
    # reference one, which with it make Figs 5 and 7 and half of Fig 6 (about 2 h each on one
    # thread, 50 min on two); Fig 8 (nine 2121-particle runs with the perturbed-lattice ensemble,
    # 30-45 CPU-min each); the coarse series of Figs 9 and 10 (about 15 CPU-min each); then the
    # long ones: Fig 6 at mu = 0.5 and 0.65 and the fine series of Figs 9 and 10 (2-2.5 h each on
    # one thread).
    compute --case afrasiabi2021/fig03 --case afrasiabi2021/table1
    compute --case afrasiabi2021/fig02
    compute --case afrasiabi2021/fig05
    compute --case afrasiabi2021/fig08
    compute --case afrasiabi2021/fig09 --series coarse
    compute --case afrasiabi2021/fig10 --series coarse
    compute --case afrasiabi2021/fig06
    compute --case afrasiabi2021/fig09
    compute --case afrasiabi2021/fig10
    ;;
  efg)
    # Kahwash, the paper's failure model (no erosion): every run goes on to the first sudden drop of
    # the critical time step (the paper's Algorithm 3.6), while the squeezed degraded chip root
    # lowers the step gradually before it (kahwash2018 FINDINGS F15); a step collapsed below 1e-3 of
    # its initial value is an ERROR. Measured with the time-step factor 0.9: the node study's
    # 2,574-, 4,573- and 7,266-node runs take 60, 42 and 145 s on one thread beside an MPM campaign
    # run (completion at 68, 37 and 41 um of travel; 27,772, 8,372 and 21,472 steps). 25 distinct runs: Figs 6-10 use
    # Table 4's runs at 30 and 75 deg (which keep the damage snapshots), the node study's 0.0096 mm
    # run is Table 4's LaRC02 30 deg; Table 4's erosion comparison adds two LaRC02 runs (30 and 75 deg)
    # with erosion. Order: the node study, then Hashin and the time-scaling points, LaRC02, the
    # erosion pair, and maximum stress last.
    compute --case kahwash2018/table2 --case kahwash2018/table6
    compute --case kahwash2018/table4 --series efg_hashin --series time_scaling
    compute --case kahwash2018/table4 --series efg_larc02
    compute --case kahwash2018/table4 --series efg_larc02_erosion
    compute --case kahwash2018/table4 --series efg_max_stress
    compute --case kahwash2018/fig06 --case kahwash2018/fig08 --case kahwash2018/fig09 --case kahwash2018/fig10
    ;;
  mpm)
    # Nairn: every paper-resolution run has 15 particles through the chip (about 30,000 particles;
    # 162,000 steps at the time step of NairnMPM's default factor 0.5, whatever the depth of cut: the
    # geometry, the run length and the step all scale with h), about 4.9e9 particle-steps, 20-25 min
    # on one thread of this machine with USAVG alone, about 45 min each with two side by side. 93 distinct runs, about 88.5 runs' worth of N = 15 work
    # (solvers/mpm/README.md, "Paper-resolution campaign"). Order: the paper's central claims first
    # (Fig 4, whose run Figs 3 and 5 share; the Fig 9 pair), then the Fig 8 transition sweep at
    # alpha = 30 deg (shared by Figs 9-12) with the cheap N = 4 and 8 convergence runs, the other rake
    # angles (Figs 8, 10, 16), friction (Figs 11, 15), hardening (Figs 12, 13), sigma_c (Fig 14),
    # Fig 16's own bending runs. The N = 20 convergence runs (2.4 runs' worth each) come right after
    # the other rake angles, so that Fig 8, the paper's central figure, is complete first. Two
    # copies of this script (one per core, started a few seconds apart) work through it together:
    # the run store's locks keep them on different runs, and each leaves to the other the runs it
    # is computing (--skip-running).
    compute --case nairn2015/fig04 --case nairn2015/fig09
    compute --case nairn2015/fig03 --case nairn2015/fig02 --case nairn2015/fig05 --case nairn2015/fig17
    compute --case nairn2015/fig08 --series mpm --series convergence_n4 --series convergence_n8
    compute --case nairn2015/fig08 --series mpm_a5 --series mpm_a15 --series mpm_a45
    compute --case nairn2015/fig08 --series convergence_n20 --series convergence_touch
    compute --case nairn2015/fig10
    compute --case nairn2015/fig11 --case nairn2015/fig15
    compute --case nairn2015/fig12 --case nairn2015/fig13
    compute --case nairn2015/fig14 --case nairn2015/fig16
    compute --case nairn2015/fig08
    ;;
  *)
    echo "usage: scripts/full-tier-campaign.sh sph|efg|mpm [cutbench executable]" >&2
    exit 2
    ;;
esac
"$cutbench" runs "$store"
exit "$failed"
