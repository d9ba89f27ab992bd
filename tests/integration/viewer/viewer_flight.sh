#!/usr/bin/env bash
# mmh-viewer with a real flight, over udpm:// in a private network namespace (loopback only): a
# lock-step flight (mmh-stack --log) is played by lcm-logplayer in real time into a running
# mmh-viewer while (1) the Foxglove protocol's own client (@foxglove/ws-protocol, node) sees the
# channels with their schemas and receives odometry and trajectories, and (2) headless Chromium
# opens the page late in the flight (snapshot first, then deltas), waits until it shows live
# services, a committed trajectory, map voxels and decisions, checks the DOM and takes a
# screenshot, which must not be blank. Also measures mmh-viewer's CPU share during the playback.
# The planners publish their debug channel (PLAN_DEBUG) in this flight, as in the demo, so the
# page must draw the debug layer. Then `mmh-viewer --log` serves the same log and Chromium scrubs
# it with the time slider (log_page_check.mjs).
# Screenshots and CPU report in BUILD/test-output/ (viewer.png, viewer-log.png, viewer-cpu.txt).
set -euo pipefail
source "$(dirname "$0")/browser_test_env.sh"
pids=()
cleanup() { for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done; wait 2>/dev/null || true; }
trap 'cleanup; rm -rf "$out"' EXIT
fail() { echo "FAIL: $*"; tail -20 "$out"/*.log 2>/dev/null; exit 1; }
port=18765

"$build/bin/mmh-stack" --density 0.1 --seed 7 --log-level error --log "$out/flight.lcm" \
  --set som.publish_debug=true --set eam.publish_debug=true > /dev/null ||
  fail "lock-step flight failed"
debug_msgs=$(python3 "$root/tests/integration/deploy/log_channels.py" "$out/flight.lcm" |
  awk '$1 == "PLAN_DEBUG" { print $2 }')
[ "${debug_msgs:-0}" -gt 0 ] || fail "no PLAN_DEBUG in the flight with publish_debug on"

"$build/bin/mmh-viewer" --bind 127.0.0.1:$port > "$out/viewer.log" 2>&1 &
viewer=$!
pids+=("$viewer")
for _ in $(seq 50); do grep -q serving "$out/viewer.log" && break; sleep 0.1; done
grep -q "serving http://127.0.0.1:$port/" "$out/viewer.log" || fail "mmh-viewer did not start"
curl -sf "http://127.0.0.1:$port/" | grep -q "viewer.js" || fail "GET / did not serve the page"
[ "$(curl -s -o /dev/null -w '%{http_code}' "http://127.0.0.1:$port/../../etc/passwd")" = 404 ] ||
  fail "a path outside the page was not refused"

(cd "$web/test" && exec node --no-warnings --experimental-websocket foxglove_client_check.mjs \
  "ws://127.0.0.1:$port/" 25 > "$out/foxglove.log" 2>&1) &
foxglove=$!
pids+=("$foxglove")
sleep 0.5

cpu_before=$(cpu_ticks "$viewer")
start_ns=$(date +%s%N)
lcm-logplayer "$out/flight.lcm" > "$out/logplayer.log" 2>&1 &
player=$!
pids+=("$player")
sleep 2 # the page connects in mid-flight: snapshot first
(cd "$web/test" && exec node page_check.mjs "http://127.0.0.1:$port/" "$results/viewer.png" 5 25 1 \
  > "$out/page.log" 2>&1) &
page=$!
pids+=("$page")

wait "$player" || fail "lcm-logplayer failed"
cpu_after=$(cpu_ticks "$viewer")
elapsed_ns=$(( $(date +%s%N) - start_ns ))
wait "$foxglove" || { cat "$out/foxglove.log"; fail "the Foxglove client check failed"; }
cat "$out/foxglove.log"
wait "$page" || { cat "$out/page.log"; fail "the page check failed"; }
cat "$out/page.log"

cpu=$(cpu_share $((cpu_after - cpu_before)) "$elapsed_ns")
maps=$(python3 "$root/tests/integration/deploy/log_channels.py" "$out/flight.lcm" | awk '$1 == "LOCAL_MAP" { print $2 }')
report="mmh-viewer CPU: $cpu % of one core over $((elapsed_ns / 1000000)) ms of playback ($maps LOCAL_MAP at 15 Hz, 100 Hz ODOMETRY, 2 clients)"
echo "$report" | tee "$results/viewer-cpu.txt"
cpu_guard "$cpu" || fail "mmh-viewer used $cpu % of a core"

colors=$(convert "$results/viewer.png" -format %k info:)
[ "${colors:-0}" -gt 500 ] || fail "the screenshot looks blank ($colors colours)"
echo "screenshot: $results/viewer.png ($colors colours)"
kill "$viewer"
wait "$viewer" || fail "mmh-viewer did not stop cleanly on SIGTERM"
pids=()
grep -q "stopped cleanly" "$out/viewer.log" || fail "no clean stop in the viewer's log"

# The recorded flight with the time slider (no LCM: nothing is played into it).
log_port=$((port + 1))
"$build/bin/mmh-viewer" --log "$out/flight.lcm" --bind 127.0.0.1:$log_port > "$out/log-viewer.log" 2>&1 &
viewer=$!
pids+=("$viewer")
for _ in $(seq 100); do grep -q serving "$out/log-viewer.log" && break; sleep 0.1; done
grep -q "serving http://127.0.0.1:$log_port/" "$out/log-viewer.log" || fail "mmh-viewer --log did not start"
grep -E "messages \(0 refused\)" "$out/log-viewer.log" || fail "mmh-viewer --log refused messages of the log"
(cd "$web/test" && exec node log_page_check.mjs "http://127.0.0.1:$log_port/" "$results/viewer-log.png" 1 30 \
  > "$out/log-page.log" 2>&1) || { cat "$out/log-page.log"; fail "the log page check failed"; }
cat "$out/log-page.log"
colors=$(convert "$results/viewer-log.png" -format %k info:)
[ "${colors:-0}" -gt 500 ] || fail "the log page's screenshot looks blank ($colors colours)"
kill "$viewer"
wait "$viewer" || fail "mmh-viewer --log did not stop cleanly on SIGTERM"
pids=()
grep -q "stopped cleanly" "$out/log-viewer.log" || fail "no clean stop in mmh-viewer --log's log"
echo PASS
