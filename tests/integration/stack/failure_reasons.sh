#!/usr/bin/env bash
# Every failed flight says why (lock-step, deterministic): a flight cut short by --timeout has
# "reason" in mmh-stack's JSON and in mmh-bench's results.json; a success has none in the JSON.
set -euo pipefail
build=$1
fail() { echo "FAIL: $*"; exit 1; }
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT

status=0
json=$("$build/bin/mmh-stack" --log-level error --json --density 0.05 --seed 5 --timeout 2) \
  || status=$?
echo "$json"
[ $status -eq 3 ] || fail "a timed-out flight exited with $status"
grep -q '"result": "timeout", "reason": "timeout: not reached after 2.0 s, ' <<< "$json" \
  || fail "no reason for the timeout"

"$build/bin/mmh-bench" --densities 0.05 --maps 1 --trials 1 --methods mmh,ego --timeout 2 \
  --no-plots --out "$dir/bench" > /dev/null 2> "$dir/err" || fail "mmh-bench: $(cat "$dir/err")"
python3 - "$dir/bench/results.json" <<'PY' || exit 1
import json, sys
results = json.load(open(sys.argv[1]))
if len(results) != 2:
    print("FAIL: %d flights" % len(results)); sys.exit(1)
for r in results:
    if r["success"]:
        print("FAIL: a 2 s flight succeeded"); sys.exit(1)
    if not (r["error"] or r["reason"]):
        print("FAIL: a failed flight without error or reason:", r); sys.exit(1)
    if not r["reason"].startswith("timeout: not reached after 2.0 s"):
        print("FAIL: reason", r["reason"]); sys.exit(1)
    print(r["method"], "->", r["reason"])
PY
json=$("$build/bin/mmh-stack" --log-level error --json --density 0.05 --seed 5) \
  || fail "the flight failed: $json"
! grep -q '"reason"' <<< "$json" || fail "a success with a reason: $json"
echo PASS
