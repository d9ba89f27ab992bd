#!/usr/bin/env bash
# Plain lcm-logplayer with a lock-step log (mmh-stack --log), over udpm:// in a private network
# namespace: played whole, mmh-mission-report sees the recorded mission; its inputs alone
# (GOAL, ODOMETRY, POINTCLOUD) played into running mapping, awareness, modes and arbiter make
# them map, plan and decide anew, as a recorder (deploy/launch/logger.sh) shows.
set -euo pipefail
build=$1
root=$(cd "$(dirname "$0")/../../.." && pwd)
if [ "${MMH_IN_NETNS:-0}" != 1 ]; then exec "$root/tests/integration/netns.sh" bash "$0" "$@"; fi
out=$(mktemp -d)
export MMH_BIN_DIR=$build/bin MMH_RUN_DIR=$out/run
cleanup() {
  "$root/deploy/launch/stack.sh" stop >/dev/null 2>&1 || true
  "$root/deploy/launch/logger.sh" stop >/dev/null 2>&1 || true
}
trap 'cleanup; rm -rf "$out"' EXIT
fail() { echo "FAIL: $*"; for f in "$out"/run/*.log; do echo "== $f"; tail -5 "$f"; done; exit 1; }
count() { python3 "$root/tests/integration/deploy/log_channels.py" "$1" | awk -v c="$2" '$1 == c { print $2 }'; }

"$build/bin/mmh-stack" --density 0.1 --seed 7 --start=-6,0,1.2 --goal 6,0,1.2 --log-level error \
  --log "$out/flight.lcm" > /dev/null || fail "lock-step flight failed"

# To watch: the whole log, no service running.
"$build/bin/mmh-mission-report" --timeout 30 > "$out/report.txt" &
report=$!
sleep 0.5
lcm-logplayer -s 4 "$out/flight.lcm"
wait $report || { cat "$out/report.txt"; fail "mmh-mission-report did not see the mission"; }
grep -qi reached "$out/report.txt" || fail "the report does not say reached"
echo "watch: ok"

# To recompute: the planner services and a recorder, then only the inputs.
"$root/deploy/launch/stack.sh" start
MMH_RECORD_FILE=$out/replayed.lcm "$root/deploy/launch/logger.sh" start
sleep 0.5
lcm-logplayer -e '^(GOAL|ODOMETRY|POINTCLOUD)$' "$out/flight.lcm"
sleep 1
"$root/deploy/launch/logger.sh" stop
cleanup
python3 "$root/tests/integration/deploy/log_channels.py" "$out/replayed.lcm.00"
for channel in LOCAL_MAP AWARENESS PLAN_RESULT TRAJECTORY ARBITER_STATUS; do
  n=$(count "$out/replayed.lcm.00" $channel)
  [ "${n:-0}" -gt 0 ] || fail "the running services published no $channel during the replay"
done
"$build/bin/mmh-log-summary" --decisions "$out/replayed.lcm.00" > "$out/summary.txt"
grep -q committed "$out/summary.txt" || fail "no committed decision in the replay"
echo PASS
