#!/usr/bin/env bash
# Lock-step flights of the mission cases (mmh-stack: deterministic, a few seconds each): a
# 4-waypoint mission through the forest, flown through mmh-setpoint and the tracking model,
# passes the middle waypoints without stopping and stops at the last, with its tracking error
# reported; the 0.1 obs/m^2 forest flown through setpoints reaches the goal; a start, goal or
# waypoint outside the geofence, and a bad waypoint, stop at once with a message naming them.
set -euo pipefail
build=$1
fail() { echo "FAIL: $*"; exit 1; }
stack=("$build/bin/mmh-stack" --log-level error --json)

json=$("${stack[@]}" --density 0.05 --seed 5 --start=-10,0,1.2 --follow setpoint \
  "--waypoints=-6,2,1.2;-1,-1.5,1.2;4,1.5,1.2;10,0,1.2") || fail "the mission failed: $json"
echo "$json"
python3 - "$json" <<'PY' || exit 1
import json, sys
r = json.loads(sys.argv[1])
def fail(why):
    print("FAIL:", why)
    sys.exit(1)
if r["result"] != "reached":
    fail("result " + r["result"])
arrivals = r["arrivals"]
if [a["waypoint"] for a in arrivals] != [1, 2, 3, 4]:
    fail("arrivals %s" % arrivals)
for a in arrivals[:3]:
    if a["speed_mps"] < 0.5:
        fail("waypoint %d passed at %.2f m/s: it stopped" % (a["waypoint"], a["speed_mps"]))
if arrivals[3]["speed_mps"] > 0.2:
    fail("the last waypoint reached at %.2f m/s" % arrivals[3]["speed_mps"])
if not all(b["time_s"] > a["time_s"] for a, b in zip(arrivals, arrivals[1:])):
    fail("arrivals out of order")
if not (0 < r["tracking_error_rms_m"] <= r["tracking_error_max_m"] < 0.3):
    fail("tracking error %s" % r)
PY

json=$("${stack[@]}" --density 0.1 --seed 7 --follow setpoint) || fail "the setpoint forest flight failed: $json"
echo "$json"
grep -q '"tracking_error_rms_m"' <<< "$json" || fail "no tracking error reported"

# Bad input: refused at once, with the reason.
check_refused() {
  local expect=$1
  shift
  local out status=0
  out=$("$build/bin/mmh-stack" --log-level error "$@" 2>&1) || status=$?
  [ $status -ne 0 ] || fail "mmh-stack $* did not fail"
  grep -qF -- "$expect" <<< "$out" || fail "mmh-stack $*: '$out' lacks '$expect'"
  echo "refused as expected: $out"
}
check_refused "geofence.max_m = [30, 30, 2.7]" --start 0,0,1.5 --goal 40,0,1.5
check_refused "the start [0, 0, 0.1] lies outside the geofence (z = 0.1 < 0.3)" --start 0,0,0.1
check_refused "waypoint 2 [50, 0, 1.2] lies outside the geofence" --waypoints "1,0,1.2;50,0,1.2"
check_refused "waypoint 2 '1,x,1'" --waypoints "1,0,1.2;1,x,1"
status=0
out=$("$build/bin/mmh-goal" --goal 40,0,1.5 --count 1 2>&1) || status=$?
[ $status -eq 2 ] || fail "mmh-goal accepted a goal outside the fence (exit $status): $out"
grep -qF "geofence.min_m" <<< "$out" || fail "mmh-goal: $out"
echo PASS
