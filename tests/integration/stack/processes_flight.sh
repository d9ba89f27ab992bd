#!/usr/bin/env bash
# The same mission with every service as a separate process over udpm:// (LCM's default URL,
# ttl=0) inside a private network namespace, launched with the project's launch scripts, in real
# time: the vehicle reaches the goal without collision, and the launch scripts stop everything.
# A ground station watches it as a user would: deploy/record.sh records the flight and mmh-top
# shows every service; mmh-log-summary reads the recording.
set -euo pipefail
build=$1
root=$(cd "$(dirname "$0")/../../.." && pwd)
if [ "${MMH_IN_NETNS:-0}" != 1 ]; then exec "$root/tests/integration/netns.sh" bash "$0" "$@"; fi
run=$(mktemp -d)
export MMH_BIN_DIR=$build/bin
recorder=""
cleanup() {
  "$root/deploy/launch/stack.sh" stop --run-dir "$run" >/dev/null 2>&1 || true
  if [ -n "$recorder" ]; then kill -INT "$recorder" 2>/dev/null || true; wait "$recorder" 2>/dev/null || true; recorder=""; fi
}
trap 'cleanup; rm -rf "$run"' EXIT
"$root/deploy/launch/stack.sh" start --run-dir "$run" \
  --sim-args "--world forest --density 0.1 --seed 7 --realtime" --goal 19.95,0,1.2
"$root/deploy/launch/stack.sh" status --run-dir "$run"
"$root/deploy/record.sh" "$run/flight.lcm" --quiet 2> "$run/record.out" &
recorder=$!
"$build/bin/mmh-top" --once --duration 3 > "$run/top.txt" || { echo "FAIL: mmh-top saw no HEARTBEAT"; exit 1; }
status=0
"$build/bin/mmh-mission-report" --timeout 90 || status=$?
if [ $status -ne 0 ]; then
  echo "FAIL: mission not completed (status $status)"
  for f in "$run"/*.log; do echo "== $f"; tail -5 "$f"; done
  exit 1
fi
cleanup

echo "--- mmh-top"; cat "$run/top.txt"
for service in mmh-mapping mmh-awareness mmh-fpm mmh-som mmh-eam mmh-arbiter mmh-sim; do
  grep -q "$service" "$run/top.txt" || { echo "FAIL: mmh-top does not show $service"; exit 1; }
done
grep -q "SILENT" "$run/top.txt" && { echo "FAIL: mmh-top shows a silent service"; exit 1; }
# record.sh named the log FILE.00 and said so; lcm-logger's log holds the whole flight.
grep -q "recording to $run/flight.lcm.00" "$run/record.out" || { echo "FAIL: record.sh did not name $run/flight.lcm.00"; cat "$run/record.out"; exit 1; }
"$build/bin/mmh-log-summary" "$run/flight.lcm.00" > "$run/summary.txt"
echo "--- mmh-log-summary"; cat "$run/summary.txt"
for channel in ODOMETRY POINTCLOUD LOCAL_MAP AWARENESS TRAJECTORY ARBITER_STATUS HEARTBEAT GOAL; do
  grep -q "^ *$channel " "$run/summary.txt" || { echo "FAIL: the recording lacks $channel"; exit 1; }
done
# A second recording to the same name never overwrites the first.
size=$(stat -c %s "$run/flight.lcm.00")
"$root/deploy/record.sh" "$run/flight.lcm" --quiet 2> /dev/null &
recorder=$!
sleep 1
kill -INT "$recorder"; wait "$recorder" 2>/dev/null || true; recorder=""
[ -e "$run/flight.lcm.01" ] && [ "$(stat -c %s "$run/flight.lcm.00")" = "$size" ] ||
  { echo "FAIL: the second recording did not go to flight.lcm.01"; exit 1; }
# Every service stopped and its pid file is gone.
if "$root/deploy/launch/stack.sh" status --run-dir "$run" | grep -q running; then
  echo "FAIL: services still running after stop"; exit 1
fi
ls "$run"/*.pid >/dev/null 2>&1 && { echo "FAIL: pid files left"; exit 1; }
echo PASS
