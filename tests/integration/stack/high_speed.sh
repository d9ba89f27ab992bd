#!/usr/bin/env bash
# A faster vehicle with a longer-range sensor flies the 0.1 obs/m^2 forest in lock-step without
# collision: 6 m/s and 6 m/s^2 with a 10 m LiDAR, and 10 m/s and 10 m/s^2 with a 20 m LiDAR (the
# planning horizon shortened so that the local target stays inside the 32 m map window). A
# configuration that could not stop within its sensor's range is refused at start-up, naming
# the keys.
set -euo pipefail
build=$1
fly() {  # fly SPEED RANGE HORIZON
  local json
  json=$("$build/bin/mmh-stack" --density 0.1 --seed 7 --sensor lidar --log-level error --json \
    --set vehicle.max_vel_mps="$1" --set vehicle.max_acc_mps2="$1" --set sim.lidar.range_m="$2" \
    --set mapping.max_range_m="$2" --set awareness.sensor_range_m="$2" \
    --set arbiter.planning_horizon_s="$3") || true
  echo "$1 m/s: $json" | cut -c1-200
  grep -q '"result": "reached"' <<< "$json" || { echo "FAIL: not reached at $1 m/s"; exit 1; }
}
fly 6 10 2.5
fly 10 20 1.5
status=0
out=$("$build/bin/mmh-stack" --density 0.1 --seed 7 --sensor lidar --log-level error \
  --set vehicle.max_vel_mps=10 --set vehicle.max_acc_mps2=10 \
  --set arbiter.planning_horizon_s=1.5 --timeout 5 2>&1) || status=$?
[ $status -ne 0 ] || { echo "FAIL: 10 m/s with a 5 m LiDAR was accepted"; exit 1; }
grep -q "awareness.sensor_range_m" <<< "$out" && grep -q "vehicle.max_vel_mps" <<< "$out" ||
  { echo "FAIL: the refusal does not name the keys: $out"; exit 1; }
echo "refused: $(grep -m1 max_vel <<< "$out")"
echo PASS
