#!/usr/bin/env bash
# A 3-waypoint mission flown through the chain a real vehicle uses, every service its own process
# over udpm:// (LCM's default URL, ttl=0) in a private network namespace, in real time: the
# arbiter's TRAJECTORY goes to mmh-setpoint, whose SETPOINT stream mmh-sim flies through its
# tracking model (--follow setpoint), and mmh-goal --waypoints hands the waypoints over. Checks:
# every waypoint reached in order, the middle ones passed at speed, the last one stopped at, the
# tracking error reported and small, the trajectory server's watchdog quiet.
set -euo pipefail
build=$1
root=$(cd "$(dirname "$0")/../../.." && pwd)
if [ "${MMH_IN_NETNS:-0}" != 1 ]; then exec "$root/tests/integration/netns.sh" bash "$0" "$@"; fi
run=$(mktemp -d)
export MMH_BIN_DIR=$build/bin
launch=$root/deploy/launch
cleanup() {
  "$launch/goal.sh" stop --run-dir "$run" >/dev/null 2>&1 || true
  "$launch/stack.sh" stop --run-dir "$run" --with-setpoint >/dev/null 2>&1 || true
}
trap 'cleanup; rm -rf "$run"' EXIT
fail() {
  echo "FAIL: $*"
  for f in "$run"/*.log; do echo "== $f"; tail -8 "$f"; done
  exit 1
}

"$launch/stack.sh" start --run-dir "$run" --with-setpoint \
  --sim-args "--world forest --density 0.05 --seed 5 --start -10,0,1.2 --goal 10,0,1.2 --realtime --follow setpoint"
"$launch/goal.sh" start --run-dir "$run" -- --waypoints="-4,1.5,1.2;3,-1.5,1.2;10,0,1.2"
status=0
report=$("$build/bin/mmh-mission-report" --timeout 120) || status=$?
echo "$report"
[ $status -eq 0 ] || fail "mission not completed (mmh-mission-report exit $status)"
grep -q "waypoints:      3 of 3 reached" <<< "$report" || fail "not every waypoint reached"
for i in 1 2 3; do
  grep -q "^  waypoint $i:" <<< "$report" || fail "no arrival at waypoint $i"
done
# The middle waypoints are passed at speed, the last one is stopped at.
# "  waypoint 2:    at 7.04 s, 1.88 m/s": the speed is the sixth field.
speed() { awk -v w="  waypoint $1:" 'index($0, w) == 1 { gsub(/,/, ""); print $6 + 0 }' <<< "$report"; }
for i in 1 2; do
  awk -v s="$(speed $i)" 'BEGIN { exit !(s + 0 > 0.5) }' || fail "waypoint $i passed at $(speed $i) m/s (not at speed)"
done
awk -v s="$(speed 3)" 'BEGIN { exit !(s + 0 <= 0.2) }' || fail "the last waypoint reached at $(speed 3) m/s"
# The tracking error is measured and reported, and small against the 1 m tolerance.
line=$(grep "^tracking error:" <<< "$report") || fail "no tracking error in the report"
rms=$(awk '{ print $4 }' <<< "$line")
max=$(awk '{ print $7 }' <<< "$line")
awk -v r="$rms" -v m="$max" 'BEGIN { exit !(r + 0 > 0 && r + 0 < 0.3 && m + 0 < 1.0 && m + 0 >= r + 0) }' ||
  fail "tracking error rms $rms m, max $max m"
# mmh-goal walked the mission to its end; the trajectory server's watchdog never tripped.
sleep 1.5
grep -q "mission done: 3 of 3 waypoints reached" "$run/mmh-goal.log" || fail "mmh-goal did not finish the mission"
grep -q "watchdog" "$run/mmh-setpoint.log" && fail "the setpoint watchdog tripped"
grep -q "trajectory_jumps\|jumped" "$run/mmh-sim.log" && fail "the vehicle jumped"
echo PASS
