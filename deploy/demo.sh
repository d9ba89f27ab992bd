#!/usr/bin/env bash
# The demo: a UAV flies the 40 m mission of the paper through an unknown 0.1 obs/m² forest, in
# real time, with every service as its own process talking over LCM (udpm://, LCM's default
# ttl=0). It sets up and builds first if needed, prints flight time, distance, energy,
# iterations per mode and cost per iteration, and leaves the LCM log of the flight and a picture.
#
#   deploy/demo.sh [--density D] [--seed N] [--sensor depth|lidar] [--out DIR] [--spy]
#                  [--host-network] [--viewer]
#
# By default everything runs in a private network namespace (loopback only, no root needed), so
# no packet — not even a multicast group join — leaves this machine. --host-network runs on the
# host's network instead (still ttl=0) so that lcm-spy or lcm-logger in another terminal see it;
# that needs a multicast route (see docs/operations.md#several-machines). --spy opens the project's lcm-spy alongside.
# --viewer starts mmh-viewer (docs/viewer.md) and prints its URL; a browser must reach it, so it
# implies --host-network, and the viewer stays up after the mission until Enter is pressed.
# The demo's planners publish their debug channel (som/eam.publish_debug, off on a vehicle), so
# the viewer shows SOM's corridors and EAM's guides, live or later with mmh-viewer --log.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
density=0.1 seed=7 sensor=depth spy=0 host_network=0 viewer=0
out=${MMH_DEMO_OUT:-}
while [ $# -gt 0 ]; do
  case "$1" in
    --density) density=$2; shift 2 ;;
    --seed) seed=$2; shift 2 ;;
    --sensor) sensor=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --spy) spy=1; shift ;;
    --host-network) host_network=1; shift ;;
    --viewer) viewer=1; host_network=1; shift ;;
    -h|--help) sed -n 2,16p "$0"; exit 0 ;;
    *) echo "demo.sh: unknown option $1" >&2; exit 2 ;;
  esac
done

if [ "${MMH_IN_NETNS:-0}" != 1 ]; then
  "$root/deploy/setup.sh"
  out=${out:-$root/out/demo-$(date +%Y%m%d-%H%M%S)}
  mkdir -p "$out"
  out=$(cd "$out" && pwd)
  args=(--density "$density" --seed "$seed" --sensor "$sensor" --out "$out")
  [ $spy = 1 ] && args+=(--spy)
  [ $viewer = 1 ] && args+=(--viewer)
  if [ $host_network = 0 ]; then
    exec "$root/tests/integration/netns.sh" "$0" "${args[@]}"
  fi
  export MMH_IN_NETNS=1  # on the host network: run the rest here
fi

bin=${MMH_BIN_DIR:-$root/build/bin}  # (a test points it at its build)
export MMH_BIN_DIR=$bin
run=$out/run
log=$out/flight.lcm
goal=19.95,0,1.2
mkdir -p "$run"
unset LCM_DEFAULT_URL  # LCM's default: udpm://239.255.76.67:7667?ttl=0
echo "demo: output in $out"
cleanup() {
  "$root/deploy/launch/stack.sh" stop --run-dir "$run" >/dev/null 2>&1 || true
  [ -n "${logger_pid:-}" ] && kill "$logger_pid" 2>/dev/null && wait "$logger_pid" 2>/dev/null
  [ -n "${spy_pid:-}" ] && kill "$spy_pid" 2>/dev/null
  [ $viewer = 1 ] && "$root/deploy/launch/viewer.sh" stop --run-dir "$run" >/dev/null 2>&1
  true
}
trap cleanup EXIT

lcm-logger -f "$log" >"$run/lcm-logger.log" 2>&1 &
logger_pid=$!
if [ $spy = 1 ]; then
  "$root/tools/lcm-spy" >"$run/lcm-spy.log" 2>&1 &
  spy_pid=$!
fi
if [ $viewer = 1 ]; then
  "$root/deploy/launch/viewer.sh" start --run-dir "$run" -- --bind 127.0.0.1:8765
  echo "demo: ground station: open http://127.0.0.1:8765/ in a browser"
fi
# The default configuration with the planners' debug channel on (PLAN_DEBUG).
config=$run/demo.yaml
sed 's/^\(  publish_debug:\) false/\1 true/' "$root/deploy/config/default.yaml" > "$config"
echo "demo: starting mapping, awareness, FPM, SOM, EAM, arbiter and the simulator (one process each)"
"$root/deploy/launch/stack.sh" start --run-dir "$run" --config "$config" \
  --sim-args "--world forest --density $density --seed $seed --sensor $sensor --realtime" \
  --goal "$goal" | sed 's/^/  /'
echo "demo: flying to $goal (watch: $bin/mmh-top in the same network; logs in $run)"
status=0
"$bin/mmh-mission-report" --timeout 120 || status=$?
sleep 0.5
if [ $viewer = 1 ] && [ -t 0 ]; then
  read -r -p "demo: the viewer still shows the flight at http://127.0.0.1:8765/; press Enter to stop " _ || true
fi
cleanup
trap - EXIT
echo "demo: LCM log of the flight: $log"
"$root/tools/plot-flight" "$log" "$out/flight.png" | sed 's/^plot: /demo: picture of the flight: /'
exit $status
