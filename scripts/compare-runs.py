#!/usr/bin/python3
"""Compare two stored solver runs (reports/full_tier/runs/*.run) of the same parameters computed by
different builds: the key's source identity and the provenance note ("run stored in the run cache:
...", with its length prefix) may differ, every other byte must be equal.

Usage: scripts/compare-runs.py OLD.run NEW.run   (exit 0 when equal, 1 when not)
An old run from git history: git show <commit>:reports/full_tier/runs/<file> > /tmp/old.run
"""
import re
import sys


NOTE = b"run stored in the run cache: "


def normalise(data: bytes) -> bytes:
    data = re.sub(rb"source [0-9a-f]{64}", b"source X", data)
    # every provenance note: a string, stored as its length (8 bytes, little endian) and its bytes
    out, pos = bytearray(), 0
    while (k := data.find(NOTE, pos)) >= 8:
        length = int.from_bytes(data[k - 8:k], "little")
        out += data[pos:k - 8] + b"NOTE"
        pos = k + length
    return bytes(out + data[pos:])


def main() -> int:
    if len(sys.argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    a, b = (open(p, "rb").read() for p in sys.argv[1:])
    na, nb = normalise(a), normalise(b)
    if na == nb:
        print(f"{sys.argv[2]}: equal to {sys.argv[1]} apart from the source identity and the provenance note")
        return 0
    i = next((k for k in range(min(len(na), len(nb))) if na[k] != nb[k]), min(len(na), len(nb)))
    print(f"{sys.argv[2]}: DIFFERS from {sys.argv[1]} at normalised byte {i} (lengths {len(na)}, {len(nb)})")
    return 1


if __name__ == "__main__":
    sys.exit(main())
