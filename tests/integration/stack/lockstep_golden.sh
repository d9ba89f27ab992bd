#!/usr/bin/env bash
# Lock-step flights of every arbiter policy (and one with lossy maps) must match the results in
# lockstep_golden.txt exactly (and refuse no message for its time): flight time, distance, energy,
# planning calls per mode, stops and the digest of every committed trajectory. A restructuring commit must leave them unchanged; a
# commit that changes behaviour on purpose regenerates the file and says why (one flight is flown
# again with SOM's two paths on two threads and must match its golden line too):
#   tests/integration/stack/lockstep_golden.sh build --update
set -euo pipefail
build=$1
update=${2:-}
here=$(cd "$(dirname "$0")" && pwd)
golden=$here/lockstep_golden.txt

flights=(
  "--density 0.1 --seed 7"
  "--density 0.2 --seed 3"
  "--density 0.05 --seed 11"
  "--density 0.2 --seed 5 --sensor lidar"
  "--density 0.1 --seed 7 --policy ego"
  "--density 0.1 --seed 7 --policy som"
  "--density 0.1 --seed 7 --policy mmh-no-lazy"
  "--density 0.1 --seed 7 --policy mmh-no-awareness"
  "--density 0.1 --seed 9 --map-loss 0.3"
)

# Everything but the wall-clock fields.
strip() { sed -E 's/, "(cost_ms_mean|wall_time_s)": [0-9.e+-]+//g'; }

actual=$(mktemp)
warnings=$(mktemp)
trap 'rm -f "$actual" "$warnings"' EXIT
for f in "${flights[@]}"; do
  # shellcheck disable=SC2086
  json=$("$build/bin/mmh-stack" $f --log-level warn --json 2>"$warnings" || true)
  [ -n "$json" ] || { echo "FAIL: mmh-stack $f printed nothing"; exit 1; }
  # In lock-step no service may refuse a message for its time: that would depend on how fast
  # the machine runs the steps, and the flight would no longer be the same everywhere.
  if grep "rejected_time" "$warnings"; then echo "FAIL: mmh-stack $f refused messages for their time"; exit 1; fi
  echo "$f | $(echo "$json" | strip)" >>"$actual"
done

if [ "$update" = "--update" ]; then
  cp "$actual" "$golden"
  echo "wrote $golden"
  exit 0
fi
if ! diff -u "$golden" "$actual"; then
  echo "FAIL: lock-step flights differ from $golden (lines with - are expected, + are now)."
  echo "If the change of behaviour is intended, regenerate with: $0 BUILD --update"
  exit 1
fi
# SOM's two paths planned on two threads must fly the same flight as planned in turn (every SOM
# request of the som policy's flight, many of them with two differing paths).
same="--density 0.1 --seed 7 --policy som"
# shellcheck disable=SC2086
parallel=$("$build/bin/mmh-stack" $same --set som.clearance_compare_parallel=true --log-level warn \
  --json 2>/dev/null | strip || true)
if [ "$same | $parallel" != "$(grep -F -- "$same |" "$golden")" ]; then
  echo "FAIL: mmh-stack $same with SOM's paths on two threads: $parallel"
  echo "      expected the golden line: $(grep -F -- "$same |" "$golden")"
  exit 1
fi
echo "PASS: ${#flights[@]} lock-step flights identical to $golden, and SOM on two threads the same"
