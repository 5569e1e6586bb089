#!/usr/bin/python3
"""Record the outcome of a full-tier run in the repository, so that the report shows it.

The full tier (paper resolution) takes CPU-hours and is not part of the main job. After a
`cutbench run --tier full --out DIR` this script copies each full-tier case record
DIR/<paper>/<item>.json (checks, values, statuses, software version, date, wall time) to
reports/full_tier/<paper>/<item>.json, adding a `recorded` block that says how the run was made
(binary commit, threads, run cache, machine), and the data its plots need as
reports/full_tier/<paper>/<item>.h5: the series tables and histories of DIR/<paper>/<item>.h5 and
only the snapshots the case's plots draw (their fields stored in single precision), so that the
report draws every plot from the paper-resolution run. These records are the paper-resolution
verdicts that `cutbench list` and the report lead with. A later record of the same case replaces
the earlier one. The record is written even when one of its reproduction or validation checks
carries a perturbation-audit finding (it cannot fail or cannot pass); the script then names it
and exits 1, since `cutbench audit` (a ctest gate) fails on such a record.

    /usr/bin/python3 reports/record_full_tier.py --results DIR --how "binary dbf0aff, 1 thread, ..."
"""
import argparse
import datetime
import json
import os
import sys
import tomllib

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def fail(msg):
    print("record_full_tier.py: " + msg, file=sys.stderr)
    sys.exit(2)


def write_atomic(path, obj):
    tmp = path + ".tmp"
    with open(tmp, "w", encoding="utf-8") as f:
        json.dump(obj, f, indent=1, sort_keys=True)
        f.write("\n")
    os.replace(tmp, path)


def plotted_snapshots(case_id):
    """(series, run, snapshot) triples the case's snapshot plots draw; snapshot may be negative."""
    with open(os.path.join(ROOT, "benchmarks", case_id + ".toml"), "rb") as f:
        case = tomllib.load(f)
    out = set()
    for p in case.get("plots", []):
        if p.get("kind") == "snapshot":
            out.add((p["series"], int(p.get("run", 0)), int(p.get("snapshot", -1))))
    return out


def slim_copy(src, dst, keep):
    """Copy a results HDF5 without the snapshots no plot draws; snapshot fields as float32."""
    import h5py
    import numpy as np

    def copy_attrs(a, b):
        for k, v in a.attrs.items():
            b.attrs[k] = v

    tmp = dst + ".tmp"
    with h5py.File(src, "r") as fin, h5py.File(tmp, "w") as fout:
        copy_attrs(fin, fout)

        def walk(gin, gout, path):
            copy_attrs(gin, gout)
            for name, obj in gin.items():
                sub = path + "/" + name
                if isinstance(obj, h5py.Group):
                    parts = sub.strip("/").split("/")
                    # /series/<s>/point_<k>/snapshots/<j>
                    if len(parts) == 5 and parts[0] == "series" and parts[3] == "snapshots":
                        series, run, j = parts[1], int(parts[2][len("point_"):]), int(parts[4])
                        count = len(gin)
                        if not any(s == series and r == run and (q == j or q + count == j) for s, r, q in keep):
                            continue
                    walk(obj, gout.create_group(name), sub)
                else:
                    data = obj[()]
                    snap = "/snapshots/" in sub and getattr(data, "dtype", None) is not None
                    if snap and data.dtype == np.float64 and not sub.endswith(("/x", "/y", "/xy")):
                        data = data.astype(np.float32)
                    d = gout.create_dataset(name, data=data, compression="gzip" if snap else None)
                    copy_attrs(obj, d)

        walk(fin, fout, "")
    os.replace(tmp, dst)
    return os.path.getsize(dst)


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--results", required=True, help="results directory of a full-tier `cutbench run`")
    ap.add_argument("--how", required=True, help="how the run was made (binary commit, threads, machine)")
    ap.add_argument("--into", default=os.path.join(here, "full_tier"), help="record directory")
    ap.add_argument("--case", action="append", default=[], help="record only this case id (repeatable)")
    ap.add_argument("--complete-only", action="store_true",
                    help="skip cases that are NOT RUN (a `cutbench run --stored-only` of a store that lacks some of their runs)")
    a = ap.parse_args()
    if not os.path.isdir(a.results):
        fail("--results: '%s' is not a directory (expected the --out directory of a full-tier run)" % a.results)
    if len(a.how.strip()) < 10:
        fail("--how: say how the run was made (binary commit, threads, machine), at least 10 characters")
    found = []
    for paper in sorted(os.listdir(a.results)):
        pdir = os.path.join(a.results, paper)
        if not os.path.isdir(pdir):
            continue
        for name in sorted(os.listdir(pdir)):
            if not name.endswith(".json"):
                continue
            with open(os.path.join(pdir, name), encoding="utf-8") as f:
                rec = json.load(f)
            if rec.get("tier") != "full" or not rec.get("case"):
                continue
            if a.case and rec["case"] not in a.case:
                continue
            if a.complete_only and rec.get("status") == "NOT RUN":
                print("not recorded %s: NOT RUN (runs missing from the store)" % rec["case"])
                continue
            found.append(rec)
    if not found and a.complete_only:
        print("nothing to record: no case is complete")
        return
    if not found:
        fail("--results: no full-tier case record (<paper>/<item>.json with tier = full) in '%s'" % a.results)
    missing = set(a.case) - {r["case"] for r in found}
    if missing:
        fail("--case: no full-tier record for %s in '%s'" % (", ".join(sorted(missing)), a.results))
    now = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ")
    vacuous = 0
    for rec in found:
        paper, item = rec["case"].split("/", 1)
        rec["recorded"] = {"how": a.how.strip(), "recorded_at": now}
        os.makedirs(os.path.join(a.into, paper), exist_ok=True)
        write_atomic(os.path.join(a.into, paper, item + ".json"), rec)
        size = ""
        h5 = os.path.join(a.results, paper, item + ".h5")
        if os.path.exists(h5):
            n = slim_copy(h5, os.path.join(a.into, paper, item + ".h5"), plotted_snapshots(rec["case"]))
            size = ", plot data %.0f kB" % (n / 1024.0)
        print("recorded %s (%s, %d checks, run %s%s)" % (rec["case"], rec.get("status"), len(rec.get("checks", [])),
                                                         rec.get("date"), size))
        for ch in rec.get("checks", []):
            if ch.get("audit") and ch.get("kind") in ("reproduction", "validation"):
                print("  VACUOUS %s %s: %s (`cutbench audit`, a ctest gate, fails on this record)"
                      % (rec["case"], ch.get("key"), ch["audit"]), file=sys.stderr)
                vacuous += 1
    if vacuous:
        sys.exit(1)


if __name__ == "__main__":
    main()
