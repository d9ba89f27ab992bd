#!/usr/bin/env bash
# The real mmh-fpm process over udpm:// in a private network namespace: requests in, feasible
# trajectories (checked by mmh-plan-request: start state, target at rest, exact limits) or
# failed results with the right reason out; the service survives bad requests and stops cleanly.
set -euo pipefail
build=$1
here=$(cd "$(dirname "$0")/.." && pwd)
if [ "${MMH_IN_NETNS:-0}" != 1 ]; then exec "$here/netns.sh" bash "$0" "$@"; fi

url="udpm://239.255.76.67:7667?ttl=0"
tmp=$(mktemp -d)
"$build/bin/mmh-fpm" --lcm-url "$url" --prefix IT_ > "$tmp/fpm.log" 2>&1 &
pid=$!
cleanup() { kill "$pid" 2>/dev/null || true; wait "$pid" 2>/dev/null || true; rm -rf "$tmp"; }
trap cleanup EXIT

req() { "$build/bin/mmh-plan-request" --lcm-url "$url" --prefix IT_ --mode fpm --timeout 15 "$@"; }

echo "--- rest to rest, 15 m"
req --start 0,0,1.2 --target 15,0,1.2
echo "--- moving and accelerating start"
req --start 0,0,1.2 --velocity 2.5,1,0.1 --acceleration 0,-0.5,0 --target 10,-5,1.5
echo "--- through waypoints"
req --start 0,0,1.2 --target 10,10,1.2 --waypoints "10,0,1.2"
echo "--- bad requests: a failed PLAN_RESULT with the reason, no crash"
req --start 0,0,1.2 --target 40,0,1.2 --expect failed --expect-reason 5   # outside the geofence
req --start 0,0,1.2 --velocity 4,0,0 --target 10,0,1.2 --expect failed --expect-reason 10
req --start 0,0,1.2 --target 0,0,1.2 --expect failed --expect-reason 11
echo "--- still answering"
req --start 5,5,1.5 --target -5,-5,1.0

kill -0 "$pid" || { echo "FAIL: mmh-fpm died"; cat "$tmp/fpm.log"; exit 1; }
kill -TERM "$pid"
status=0
wait "$pid" || status=$?
[ "$status" -eq 0 ] || { echo "FAIL: mmh-fpm exited with $status"; cat "$tmp/fpm.log"; exit 1; }
grep -q "stopped cleanly" "$tmp/fpm.log" || { echo "FAIL: no clean stop"; cat "$tmp/fpm.log"; exit 1; }
echo "PASS"
