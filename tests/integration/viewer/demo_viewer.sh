#!/usr/bin/env bash
# `deploy/demo.sh --viewer` as a newcomer runs it, in a private network namespace (loopback only:
# the demo's "host network" is then this namespace's): the demo prints the ground station's URL,
# headless Chromium opens it while the real processes fly the mission and waits until the page
# shows the seven services alive, a committed trajectory, map voxels, decisions and then "goal
# reached"; none of them is still STARTING, no service refused a message for its time (heartbeats
# of idle services and of the simulator keep time with the flight); the demo reports the goal
# reached, stops the viewer with the other services and leaves its log and picture. Also
# measures the viewer's CPU share. Screenshot: BUILD/test-output/viewer-demo.png.
set -euo pipefail
source "$(dirname "$0")/browser_test_env.sh"
demo=""
cleanup() { [ -n "$demo" ] && kill "$demo" 2>/dev/null; wait 2>/dev/null || true; }
trap 'cleanup; rm -rf "$out"' EXIT
fail() { echo "FAIL: $*"; tail -30 "$out/demo.log" 2>/dev/null; exit 1; }

# stdin is not a terminal: the demo does not wait for Enter after the mission.
MMH_BIN_DIR=$build/bin "$root/deploy/demo.sh" --viewer --out "$out/demo" < /dev/null \
  > "$out/demo.log" 2>&1 &
demo=$!
url=""
for _ in $(seq 300); do
  url=$(grep -o 'open http://127.0.0.1:[0-9]*/' "$out/demo.log" | head -1 | cut -d' ' -f2 || true)
  [ -n "$url" ] && break
  kill -0 "$demo" 2>/dev/null || fail "the demo ended before it printed the viewer's URL"
  sleep 0.1
done
[ -n "$url" ] || fail "the demo printed no URL for the viewer"
echo "demo: viewer at $url"
# The viewer's CPU share while the demo flies (sampled until the page has seen the goal reached).
viewer_pid=$(cat "$out/demo/run/mmh-viewer.pid")
cpu_before=$(cpu_ticks "$viewer_pid")
start_ns=$(date +%s%N)
(cd "$web/test" && exec node page_check.mjs "$url" "$results/viewer-demo.png" 7 90 1) \
  > "$out/page.log" 2>&1 || { cat "$out/page.log"; fail "the page check on the demo failed"; }
cpu_after=$(cpu_ticks "$viewer_pid")
elapsed_ns=$(( $(date +%s%N) - start_ns ))
cat "$out/page.log"
cpu=$(cpu_share $((cpu_after - cpu_before)) "$elapsed_ns")
echo "mmh-viewer CPU during the demo: $cpu % of one core over $((elapsed_ns / 1000000)) ms (15 Hz maps, 100 Hz odometry, one page)" |
  tee "$results/viewer-demo-cpu.txt"
cpu_guard "$cpu" || fail "mmh-viewer used $cpu % of a core"
status=0
wait "$demo" || status=$?
demo=""
[ $status -eq 0 ] || fail "deploy/demo.sh --viewer exit code $status"
grep -q "mission: *goal reached" "$out/demo.log" || fail "the demo did not report the goal reached"
[ -s "$out/demo/flight.lcm" ] || fail "no LCM log of the flight"
[ -s "$out/demo/flight.png" ] || fail "no picture of the flight"
# Every service's heartbeats keep time with the flight: none refused for going back in time.
if grep -h "rejected_time" "$out/demo/run/"*.log; then fail "messages refused for their time"; fi
# The viewer was stopped with the demo: nothing listens on its port any more.
python3 - "$url" <<'PY' && fail "the viewer still answers after the demo"
import sys, urllib.request
try:
    urllib.request.urlopen(sys.argv[1], timeout=2)
except Exception:
    sys.exit(1)
PY
echo PASS
