#!/usr/bin/python3
"""Record the outcome of a full-tier run in the repository, so that the report shows it.

The full tier (paper resolution) takes CPU-hours and is not part of the main job. After a
`cutbench run --tier full --out DIR` this script copies each full-tier case record
DIR/<paper>/<item>.json (checks, values, statuses, software version, date, wall time) to
reports/full_tier/<paper>/<item>.json, adding a `recorded` block that says how the run was made
(binary commit, threads, run cache, machine). `make_report.py` draws these records next to the
quick-tier checks of each case. A later record of the same case replaces the earlier one.

    /usr/bin/python3 reports/record_full_tier.py --results DIR --how "binary dbf0aff, 1 thread, ..."
"""
import argparse
import datetime
import json
import os
import sys


def fail(msg):
    print("record_full_tier.py: " + msg, file=sys.stderr)
    sys.exit(2)


def write_atomic(path, obj):
    tmp = path + ".tmp"
    with open(tmp, "w", encoding="utf-8") as f:
        json.dump(obj, f, indent=1, sort_keys=True)
        f.write("\n")
    os.replace(tmp, path)


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--results", required=True, help="results directory of a full-tier `cutbench run`")
    ap.add_argument("--how", required=True, help="how the run was made (binary commit, threads, machine)")
    ap.add_argument("--into", default=os.path.join(here, "full_tier"), help="record directory")
    ap.add_argument("--case", action="append", default=[], help="record only this case id (repeatable)")
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
            found.append(rec)
    if not found:
        fail("--results: no full-tier case record (<paper>/<item>.json with tier = full) in '%s'" % a.results)
    missing = set(a.case) - {r["case"] for r in found}
    if missing:
        fail("--case: no full-tier record for %s in '%s'" % (", ".join(sorted(missing)), a.results))
    now = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ")
    for rec in found:
        paper, item = rec["case"].split("/", 1)
        rec["recorded"] = {"how": a.how.strip(), "recorded_at": now}
        os.makedirs(os.path.join(a.into, paper), exist_ok=True)
        write_atomic(os.path.join(a.into, paper, item + ".json"), rec)
        print("recorded %s (%s, %d checks, run %s)" % (rec["case"], rec.get("status"), len(rec.get("checks", [])),
                                                       rec.get("date")))


if __name__ == "__main__":
    main()
