#!/usr/bin/env bash
# Two vehicles on one network (udpm://, ttl=0, private network namespace), each started by
# deploy/launch/stack.sh with its own prefix (UAV1_, UAV2_; on several machines the groups of
# deploy/ansible/inventory/two-vehicles.yml), fly at once in two lanes 8 m apart: both reach
# their goals, every channel carries one of the two prefixes, and
# each arbiter's decisions and each vehicle's path stay in its own lane (no crosstalk).
set -euo pipefail
build=$1
root=$(cd "$(dirname "$0")/../../.." && pwd)
if [ "${MMH_IN_NETNS:-0}" != 1 ]; then exec "$root/tests/integration/netns.sh" bash "$0" "$@"; fi
out=$(mktemp -d)
stack() {  # stack VEHICLE start|stop [options]
  local v=$1 action=$2
  shift 2
  "$root/deploy/launch/stack.sh" "$action" --prefix "UAV${v}_" --run-dir "$out/uav$v" \
    --bin-dir "$build/bin" "$@"
}
cleanup() {
  for v in 1 2; do stack $v stop >/dev/null 2>&1 || true; done
  MMH_RUN_DIR=$out/all "$root/deploy/launch/logger.sh" stop >/dev/null 2>&1 || true
}
trap 'cleanup; rm -rf "$out"' EXIT
fail() {
  echo "FAIL: $*"
  for f in "$out"/*/*.log; do [ -f "$f" ] && { echo "== $f"; tail -5 "$f"; }; done
  exit 1
}

lane_y=(0 0 8)  # vehicle 1: y = 0, vehicle 2: y = 8

# Everything on the network, whatever its prefix.
MMH_RUN_DIR=$out/all MMH_RECORD_FILE=$out/all/everything.lcm "$root/deploy/launch/logger.sh" start
"$build/bin/mmh-mission-report" --prefix UAV1_ --timeout 90 > "$out/report1.txt" & r1=$!
"$build/bin/mmh-mission-report" --prefix UAV2_ --timeout 90 > "$out/report2.txt" & r2=$!
for v in 1 2; do
  y=${lane_y[$v]}
  stack $v start --sim-args "--world forest --density 0.05 --seed $v --start=-6,$y,1.2 --goal 6,$y,1.2 --realtime" \
    --goal "6,$y,1.2" || fail "stack.sh start UAV${v}_"
done
s1=0; s2=0
wait $r1 || s1=$?
wait $r2 || s2=$?
cat "$out/report1.txt" "$out/report2.txt"
[ $s1 -eq 0 ] || fail "UAV1_ did not complete its mission"
[ $s2 -eq 0 ] || fail "UAV2_ did not complete its mission"
cleanup
log=$out/all/everything.lcm.00

python3 "$root/tests/integration/deploy/log_channels.py" "$log" > "$out/channels.txt"
cat "$out/channels.txt"
# (LCM_SELF_TEST is LCM's own start-up check of every udpm:// process.)
stray=$(awk '$1 !~ /^UAV[12]_/ && $1 != "LCM_SELF_TEST" { print $1 }' "$out/channels.txt")
[ -z "$stray" ] || fail "channels without a vehicle prefix: $stray"
for v in 1 2; do
  "$build/bin/mmh-log-summary" "$log" --export-flight "$out/flight$v.json" --prefix "UAV${v}_"
  python3 - "$out/flight$v.json" "${lane_y[$v]}" "UAV${v}_" <<'PY' || fail "crosstalk for UAV${v}_"
import json, sys
flight, lane, prefix = json.load(open(sys.argv[1])), float(sys.argv[2]), sys.argv[3]
path, decisions = flight["path"], flight["decisions"]
assert path and decisions, f"{prefix}: no path or no decisions"
far = [p for p in path if abs(p[2] - lane) > 3.0] + [d for d in decisions if abs(d[2] - lane) > 3.0]
print(f"{prefix}: {len(path)} path samples, {len(decisions)} decisions, "
      f"{len(far)} outside the lane y = {lane} +- 3 m")
assert not far, f"{prefix}: samples from the other lane: {far[:3]}"
assert flight.get("mission", {}).get("reached"), f"{prefix}: not reached in the log"
PY
done
echo PASS
