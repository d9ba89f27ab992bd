#!/usr/bin/env bash
# The real mmh-awareness process over udpm:// in a private network namespace: a LOCAL_MAP
# keyframe, ODOMETRY and GOAL in (from mmh-awareness-check), AWARENESS out - clear, blocked by a
# pillar on the ray, narrow between two pillars.
set -euo pipefail
build=$1
here=$(cd "$(dirname "$0")/.." && pwd)
if [ "${MMH_IN_NETNS:-0}" != 1 ]; then exec "$here/netns.sh" bash "$0" "$@"; fi

url="udpm://239.255.76.67:7667?ttl=0"
tmp=$(mktemp -d)
"$build/bin/mmh-awareness" --lcm-url "$url" --prefix IT_ > "$tmp/awareness.log" 2>&1 &
pid=$!
cleanup() { kill "$pid" 2>/dev/null || true; wait "$pid" 2>/dev/null || true; rm -rf "$tmp"; }
trap cleanup EXIT

check() { "$build/bin/mmh-awareness-check" --lcm-url "$url" --prefix IT_ --timeout 20 "$@"; }

check --position 0.5,0,1.2 --goal 20,0,1.2 --expect clear
check --position 0.5,0,1.2 --goal 20,0,1.2 --map-pillars "3,0,0.3" --expect blocked
check --position 0.5,0,1.2 --goal 20,0,1.2 --map-pillars "3,1,0.3;3,-1,0.3" --expect narrow
check --position 0.5,0,1.2 --goal 2.0,0,1.2 --map-pillars "3,0,0.3" --expect clear  # goal before it

kill -0 "$pid" || { echo "FAIL: mmh-awareness died"; cat "$tmp/awareness.log"; exit 1; }
kill -TERM "$pid"
status=0
wait "$pid" || status=$?
[ "$status" -eq 0 ] || { echo "FAIL: mmh-awareness exited with $status"; cat "$tmp/awareness.log"; exit 1; }
echo "PASS"
