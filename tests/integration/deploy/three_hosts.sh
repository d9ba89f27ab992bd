#!/usr/bin/env bash
# Three hosts as network namespaces joined by a bridge (docs/operations.md, "Several machines"), the deployment
# started by deploy/deploy.sh from a manifest with ttl=1: vehicle (sim, mapping), planner
# (awareness, FPM, SOM, EAM, arbiter), ground station (lcm-logger, goal). The vehicle reaches the
# goal, and the ground station's log holds every channel that was on the network (a reference
# recorder on the planner host) and at least the core channels.
set -euo pipefail
build=$1
root=$(cd "$(dirname "$0")/../../.." && pwd)
# A private network namespace (no physical interface: nothing leaves the machine) as the switch.
if [ "${MMH_IN_NETNS:-0}" != 1 ]; then exec "$root/tests/integration/netns.sh" bash "$0" "$@"; fi
out=$(mktemp -d)
ns=$out/netns
mkdir -p "$ns"
holders=()
export LCM_DEFAULT_URL='udpm://239.255.76.67:7667?ttl=1'
cleanup() {
  "$root/deploy/deploy.sh" "$out/uav1.yaml" stop --netns "$ns" >/dev/null 2>&1 || true
  [ -n "${reference:-}" ] && kill "$reference" 2>/dev/null && wait "$reference" 2>/dev/null
  for pid in "${holders[@]}"; do kill "$pid" 2>/dev/null || true; done
}
trap 'cleanup; rm -rf "$out"' EXIT
fail() {
  echo "FAIL: $*"
  for f in "$out"/*/*.log; do [ -f "$f" ] && { echo "== $f"; tail -5 "$f"; }; done
  exit 1
}

ip link add mmhbr0 type bridge
ip link set mmhbr0 type bridge mcast_snooping 0
ip link set mmhbr0 up
n=1
for host in vehicle planner ground; do
  unshare -n sleep 100000 &
  holders+=($!)
  sleep 0.1
  ln -s "/proc/${holders[-1]}/ns/net" "$ns/$host"
  ip link add "mmh-$host" type veth peer name eth0 netns "${holders[-1]}"
  ip link set "mmh-$host" master mmhbr0 up
  n=$((n + 1))
  nsenter --net="$ns/$host" sh -c "ip link set lo up; ip link set eth0 up;
    ip addr add 10.213.0.$n/24 dev eth0; ip route add 224.0.0.0/4 dev eth0"
done

cat > "$out/uav1.yaml" <<YAML
prefix: UAV1_
lcm_url: $LCM_DEFAULT_URL
root: $root
bin_dir: $build/bin
hosts:
  vehicle:
    run_dir: $out/vehicle
    services:
      - mapping
      - sim: --world forest --density 0.1 --seed 1 --start=-6,0,1.2 --goal 6,0,1.2 --realtime
  planner:
    run_dir: $out/planner
    services: [awareness, fpm, som, eam, arbiter]
  ground:
    run_dir: $out/ground
    services:
      - logger
      - goal: --goal 6,0,1.2
YAML

nsenter --net="$ns/planner" lcm-logger -q "$out/reference.lcm" &
reference=$!
"$root/deploy/deploy.sh" "$out/uav1.yaml" start --netns "$ns" || fail "deploy.sh start"
"$root/deploy/deploy.sh" "$out/uav1.yaml" status --netns "$ns" || fail "deploy.sh status"
nsenter --net="$ns/ground" "$build/bin/mmh-mission-report" --prefix UAV1_ --timeout 90 ||
  fail "the ground station did not see the mission completed"
"$root/deploy/deploy.sh" "$out/uav1.yaml" stop --netns "$ns" || fail "deploy.sh stop"
status=0
"$root/deploy/deploy.sh" "$out/uav1.yaml" status --netns "$ns" > "$out/status.txt" || status=$?
[ $status -eq 3 ] || fail "status after stop: exit code $status, not 3"
grep -q running "$out/status.txt" && fail "services still running after stop"
kill "$reference"; wait "$reference" 2>/dev/null || true
reference=""

channels() { python3 "$root/tests/integration/deploy/log_channels.py" "$@" | awk '{ print $1 }'; }
echo "ground station's log:"
python3 "$root/tests/integration/deploy/log_channels.py" "$out"/ground/UAV1_flight.lcm.00
channels "$out"/ground/UAV1_flight.lcm.00 > "$out/ground.txt"
channels "$out/reference.lcm" | grep '^UAV1_' > "$out/reference.txt"
missing=$(comm -23 <(sort "$out/reference.txt") <(sort "$out/ground.txt"))
[ -z "$missing" ] || fail "on the network but not in the ground station's log: $missing"
for c in ODOMETRY POINTCLOUD GOAL LOCAL_MAP AWARENESS PLAN_RESULT TRAJECTORY ARBITER_STATUS \
  HEARTBEAT MISSION_STATUS; do
  grep -qx "UAV1_$c" "$out/ground.txt" || fail "UAV1_$c missing from the ground station's log"
done
grep -q "^UAV1_PLAN_REQUEST_" "$out/ground.txt" || fail "no PLAN_REQUEST in the ground station's log"
echo PASS
