#!/usr/bin/python3
"""The sources digest of a solver method at a git commit: the SHA-256 that cmake/source_identity.cmake
computes over the method's sources (without the build settings), so that a paper-resolution record
names the solver code that made it and `cutbench list` can tell when it is stale.

    /usr/bin/python3 reports/source_digest.py COMMIT METHOD        # prints the digest
    /usr/bin/python3 reports/source_digest.py --backfill           # records without solver_sources
"""
import hashlib
import json
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
EXTENSIONS = (".cpp", ".hpp", ".h", ".c")


def git(*args):
    return subprocess.run(["git", "-C", ROOT] + list(args), check=True, capture_output=True).stdout


def method_dirs(commit, method):
    """solvers/common, solvers/<method>, and analytic/ when the method's library links it."""
    dirs = ["solvers/common", "solvers/" + method]
    cmake = git("show", "%s:solvers/%s/CMakeLists.txt" % (commit, method)).decode()
    if "cutbench::analytic" in cmake:
        dirs.append("analytic")
    return dirs


def digest(commit, method):
    files = []
    for line in git("ls-tree", "-r", commit, "--", *method_dirs(commit, method)).decode().splitlines():
        meta, path = line.split("\t", 1)
        name = os.path.basename(path)
        if name.endswith(EXTENSIONS) or name == "CMakeLists.txt":
            files.append((path, meta.split()[2]))
    listing = ""
    for path, blob in sorted(files):
        listing += "%s  %s\n" % (hashlib.sha256(git("cat-file", "blob", blob)).hexdigest(), path)
    return hashlib.sha256(("cutbench sources v1\n" + listing).encode()).hexdigest()


def backfill():
    base = os.path.join(HERE, "full_tier")
    for paper in sorted(os.listdir(base)):
        pdir = os.path.join(base, paper)
        if not os.path.isdir(pdir) or paper == "runs":
            continue
        for name in sorted(os.listdir(pdir)):
            if not name.endswith(".json"):
                continue
            path = os.path.join(pdir, name)
            with open(path, encoding="utf-8") as f:
                rec = json.load(f)
            if rec.get("solver_sources"):
                continue
            case = rec["case"]
            with open(os.path.join(ROOT, "benchmarks", case + ".toml"), encoding="utf-8") as f:
                solver = next(l.split("=", 1)[1].strip().strip('"') for l in f if l.startswith("solver"))
            if solver == "analytic":
                continue
            commit = rec["software"].split("+", 1)[1]
            dirty = commit.endswith("+dirty")
            commit = commit.split("+", 1)[0]
            rec["solver_sources"] = digest(commit, solver)
            if dirty:
                rec["solver_sources_note"] = ("built from a working tree with uncommitted changes: the digest is "
                                              "that of commit %s" % commit)
            tmp = path + ".tmp"
            with open(tmp, "w", encoding="utf-8") as f:
                json.dump(rec, f, indent=1, sort_keys=True)
                f.write("\n")
            os.replace(tmp, path)
            print("%s: %s sources of %s%s" % (case, solver, commit, " (dirty build)" if dirty else ""))


if __name__ == "__main__":
    if sys.argv[1:] == ["--backfill"]:
        backfill()
    elif len(sys.argv) == 3:
        print(digest(sys.argv[1], sys.argv[2]))
    else:
        sys.exit(__doc__)
