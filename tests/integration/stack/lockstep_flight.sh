#!/usr/bin/env bash
# A full flight in mmh-stack (every service in one process, lock-step) through a 0.1 obs/m²
# forest reaches the goal without collision; the same seed flies the same flight again.
set -euo pipefail
build=$1
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
run() { "$build/bin/mmh-stack" --density 0.1 --seed 7 --log-level error --json; }
first=$(run) || { echo "FAIL: flight did not reach the goal: $first"; exit 1; }
echo "$first"
echo "$first" | grep -q '"result": "reached"' || { echo "FAIL: not reached"; exit 1; }
second=$(run)
# Everything but the wall-clock fields must repeat exactly.
strip() { sed -E 's/"(cost_ms_mean|wall_time_s)": [0-9.e+-]+//g'; }
[ "$(echo "$first" | strip)" = "$(echo "$second" | strip)" ] || {
  echo "FAIL: the same seed gave a different flight:"; echo "$second"; exit 1; }
echo PASS
