#!/usr/bin/python3
"""Stage the finished runs of a run store for a commit; or commit the checkpoints of its runs in progress.

    /usr/bin/python3 scripts/store_finished_runs.py [--store DIR] [--cutbench EXE] [--dry-run]
    /usr/bin/python3 scripts/store_finished_runs.py --checkpoints [--store DIR] [--dry-run]

For every run file in the store (default reports/full_tier/runs) that git does not track yet:
- the committed checkpoint of the same run, if there is one, leaves the index (`git rm --cached`,
  after lifting the assume-unchanged flag a machine may have set on it; the campaign deletes the
  checkpoint file itself when the run finishes);
- the run file is staged (`git add -f`: the store's files are ignored by default);
- a row for the store's README is printed: the run, the cases and series that read it (from the
  full-tier plan), the threads and wall time of its last process, and its main results.
Nothing is committed, and the README is not edited: the printed rows are for the hand that writes
it. Runs another live process is still computing have no run file yet and are not touched.

With --checkpoints, every checkpoint in the store (`*.ckpt`: the runs in progress) is committed
instead, so that another machine resumes those runs. A campaign rewrites a checkpoint every few
minutes (by rename), so each is copied first and the copy's blob is staged under the checkpoint's
path; the commit holds these checkpoints alone (it refuses to run while anything else is staged)
and names each run with its fraction done. The paths are then marked assume-unchanged, so that
the campaign's next rewrites do not show as changes (`scripts/store_finished_runs.py` lifts the
flag when the run finishes).
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def git(*args, check=True):
    return subprocess.run(["git", *args], cwd=ROOT, check=check, capture_output=True, text=True).stdout


def tracked(path):
    return git("ls-files", "--error-unmatch", path, check=False) != ""


def summary(solver, s):
    """The results a README row quotes, by solver."""
    def num(key, fmt):
        return fmt.format(s[key]) if key in s else None

    parts = []
    if solver == "mpm_cutting":
        if "touching" in s:
            parts.append("touching" if s["touching"] >= 0.5 else "bending")
        parts += [num("F_c", "F_c {:,.0f} N/m"), num("F_nb_over_bGc", "F_n^b {:.3f} bG_c"),
                  num("energy_residual_fraction", "energy residual {:.1%}")]
    elif solver in ("sph_cutting", "efg_cutting"):
        parts += [num("F_c", "F_c {:,.0f} N/m"), num("F_t", "F_t {:,.0f} N/m"),
                  num("energy_residual_fraction", "energy residual {:.2%}")]
    else:
        parts += [num("fc_bar", "F_c bar {:.4f}")]
    return "; ".join(p for p in parts if p)


def fraction_done(progress_path):
    """The last fraction of a run's progress file (lines "unix time, fraction"), or None."""
    try:
        with open(progress_path) as f:
            lines = [l.split() for l in f if l.strip()]
        return float(lines[-1][-1]) if lines else None
    except (OSError, ValueError, IndexError):
        return None


def commit_checkpoints(store, rel_store, dry_run):
    if git("diff", "--cached", "--name-only").strip():
        print("something else is staged: commit or unstage it first", file=sys.stderr)
        return 2
    ckpts = sorted(f for f in os.listdir(store) if f.endswith(".ckpt"))
    if not ckpts:
        print("no checkpoint in " + rel_store)
        return 0
    done = []
    with tempfile.TemporaryDirectory() as tmp:
        for f in ckpts:
            path = os.path.join(rel_store, f)
            copy = os.path.join(tmp, f)
            shutil.copyfile(os.path.join(store, f), copy)  # one consistent file: a rewrite renames
            blob = git("hash-object", "-w", copy).strip()
            if blob == git("rev-parse", "-q", "--verify", "HEAD:" + path, check=False).strip():
                print("unchanged " + path)
                continue
            frac = fraction_done(os.path.join(store, f[:-5] + ".progress"))
            at = " at %d %%" % round(100 * frac) if frac is not None else ""
            print("commit " + path + at)
            if not dry_run:
                git("update-index", "--add", "--cacheinfo", "100644,%s,%s" % (blob, path))
            done.append((path, f[:-5] + at))
    if not done or dry_run:
        return 0
    git("commit", "-q", "-m", "run store: checkpoints of the runs in progress (%s)" % ", ".join(l for _, l in done))
    for path, _ in done:
        git("update-index", "--assume-unchanged", path)
    print(git("log", "--oneline", "-1").strip())
    return 0


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--store", default="reports/full_tier/runs")
    ap.add_argument("--cutbench", default="build/release/benchmarks/cli/cutbench")
    ap.add_argument("--dry-run", action="store_true", help="print what would be staged, change nothing")
    ap.add_argument("--checkpoints", action="store_true", help="commit the checkpoints of the runs in progress")
    a = ap.parse_args()
    store = os.path.join(ROOT, a.store) if not os.path.isabs(a.store) else a.store
    exe = os.path.join(ROOT, a.cutbench) if not os.path.isabs(a.cutbench) else a.cutbench
    rel_store = os.path.relpath(store, ROOT)
    if a.checkpoints:
        return commit_checkpoints(store, rel_store, a.dry_run)

    new = sorted(f for f in os.listdir(store)
                 if f.endswith(".run") and not tracked(os.path.join(rel_store, f)))
    if not new:
        print("no finished run to stage in " + rel_store)
        return 0

    def cutbench_json(*args):
        out = subprocess.run([exe, "runs", store, "--json", *args], cwd=ROOT, check=True,
                             capture_output=True, text=True).stdout
        return json.loads(out)

    stored = {r["file"]: r for r in cutbench_json("--results")}
    readers = {}
    for case in cutbench_json("--tier", "full"):
        for r in case["runs"]:
            readers.setdefault(r["file"], []).append("%s %s %s" % (case["case"], r["series"], r["point"]))

    for f in new:
        run_path = os.path.join(rel_store, f)
        ckpt = run_path[:-4] + ".ckpt"
        if tracked(ckpt):
            print("unstage checkpoint " + ckpt)
            if not a.dry_run:
                git("update-index", "--no-assume-unchanged", ckpt)
                git("rm", "-q", "--cached", ckpt)
        print("stage " + run_path)
        if not a.dry_run:
            git("add", "-f", run_path)
        r = stored.get(f, {})
        s = r.get("scalars", {})
        threads = "%d thread%s" % (s.get("threads", 1), "" if s.get("threads", 1) == 1 else "s")
        wall = "%s s in its last process" % format(round(s["wall_time"]), ",") if "wall_time" in s else "wall time not stored"
        what = "; ".join(readers.get(f, ["read by no full-tier case"]))
        print("| `%s` | %s (%s) | %s, %s | %s |" % (f[:-4], what, r.get("differing", ""), threads, wall,
                                                   summary(r.get("solver", ""), s)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
