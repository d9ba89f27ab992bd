#!/usr/bin/env bash
# tools/lcm-spy for real: under Xvfb, in a private network namespace, with mmh-sim publishing in
# real time. Passes when lcm-spy finds the project's types, its window is up, and its channel
# table shows live channels; the screenshot is left in BUILD/test-output/lcm-spy.png.
set -euo pipefail
build=$1
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../../.." && pwd)
if [ "${MMH_IN_NETNS:-0}" != 1 ]; then exec "$here/../netns.sh" bash "$0" "$@"; fi

for tool in Xvfb xwininfo import convert java; do
  command -v "$tool" > /dev/null || { echo "FAIL: $tool not installed (deploy/setup.sh installs it)"; exit 1; }
done
out=$build/test-output
mkdir -p "$out"
shot=$out/lcm-spy.png
work=$(mktemp -d)
pids=()
cleanup() {
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null || true; done
  for pid in "${pids[@]}"; do wait "$pid" 2>/dev/null || true; done
  rm -rf "$work"
}
trap cleanup EXIT

# Xvfb picks a free display itself and writes its number to fd 3.
Xvfb -displayfd 3 -screen 0 1024x700x24 -nolisten tcp 3> "$work/display" 2> "$work/xvfb.log" &
pids+=($!)
for _ in $(seq 100); do [ -s "$work/display" ] && break; sleep 0.1; done
[ -s "$work/display" ] || { echo "FAIL: Xvfb did not start"; cat "$work/xvfb.log"; exit 1; }
export DISPLAY=:$(cat "$work/display")

"$build/bin/mmh-sim" --realtime --density 0.1 --seed 7 --duration 120 > "$work/sim.log" 2>&1 &
pids+=($!)
MMH_LCMTYPES_JAR=$build/lcmtypes/mmh_lcmtypes.jar "$root/tools/lcm-spy" > "$work/spy.log" 2>&1 &
pids+=($!)

# Rows of the channel table: lcm-spy draws a 16 px row per channel (white, text, grid line); the
# empty table is grey (#EEEEEE). Counts the non-grey pixels below the header, down the Type column.
table_rows() {
  convert "$shot" -crop 1x540+200+20 +repage -depth 8 txt:- |
    awk 'NR > 1 && $0 !~ /#EEEEEE/ { n++ } END { printf "%d\n", (n + 8) / 16 }'
}

window=0 rows=0
for _ in $(seq 60); do
  sleep 1
  if ! kill -0 "${pids[2]}" 2>/dev/null; then echo "FAIL: lcm-spy exited"; cat "$work/spy.log"; exit 1; fi
  xwininfo -root -tree | grep -q '"LCM Spy"' && window=1 || continue
  import -window root "$shot"
  rows=$(table_rows)
  [ "$rows" -ge 4 ] && break
done
# A few seconds more so the screenshot shows the rates too.
if [ "$rows" -ge 4 ]; then sleep 3; import -window root "$shot"; rows=$(table_rows); fi

echo "--- lcm-spy output"; cat "$work/spy.log"
echo "screenshot: $shot"
types=$(sed -n 's/^Found \([0-9]*\) LCM types$/\1/p' "$work/spy.log")
expected=$(ls "$root"/lcmtypes/*.lcm | wc -l)
status=0
[ "${types:-0}" -ge "$expected" ] || { echo "FAIL: lcm-spy found ${types:-no} LCM types, expected the project's $expected"; status=1; }
[ "$window" = 1 ] || { echo "FAIL: no 'LCM Spy' window on $DISPLAY"; status=1; }
# mmh-sim publishes ODOMETRY, POINTCLOUD, MISSION_STATUS and HEARTBEAT.
[ "$rows" -ge 4 ] || { echo "FAIL: the channel table shows $rows channels, expected the simulator's 4"; status=1; }
[ "$status" = 0 ] && echo "PASS: $types types, window up, $rows live channels"
exit $status
