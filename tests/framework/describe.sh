#!/usr/bin/env bash
# `cutbench describe`: every registered model and solver describes itself (text and JSON); a
# solver's JSON has its parameters with kinds and its tables; an option lists its names.
set -u
cutbench="$1"
fail=0
names=$("$cutbench" describe --json | /usr/bin/python3 -c 'import json,sys; print(" ".join(d["name"] for d in json.load(sys.stdin)))') || { echo "FAIL describe --json"; exit 1; }
for n in $names; do
  "$cutbench" describe "$n" >/dev/null || { echo "FAIL describe $n"; fail=1; }
  "$cutbench" describe "$n" --json | /usr/bin/python3 -c '
import json, sys
d = json.load(sys.stdin)
assert d["params"] is not None and "outputs" in d, d["name"]
for p in d["params"]:
    assert p["kind"] in ("real", "integer", "switch", "option"), p
    if p["kind"] == "option":
        assert p["options"] and (p["default"] is None or p["default"] in [o["name"] for o in p["options"]]), p
if d["type"] == "solver":
    for t in d["tables"]:
        assert t["columns"], t
' || { echo "FAIL describe $n --json"; fail=1; }
done
echo "described: $(echo $names | wc -w) models and solvers"
exit $fail
