#!/usr/bin/env bash
# mmh-sim (real time) and mmh-mapping as separate processes over udpm:// in a private network
# namespace; mmh-goal sends the goal; mmh-test-mapcheck flies a square next to the start and
# compares the LOCAL_MAP it receives with the forest.
set -euo pipefail
build=$1
here=$(cd "$(dirname "$0")" && pwd)
if [ "${MMH_IN_NETNS:-0}" != 1 ]; then exec "$here/../netns.sh" bash "$0" "$@"; fi

url="udpm://239.255.76.67:7667?ttl=0"
logs=$(mktemp -d)
world=(--density 0.2 --seed 5)
pids=()
cleanup() {
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null || true; done
  for pid in "${pids[@]}"; do wait "$pid" 2>/dev/null || true; done
  rm -rf "$logs"
}
trap cleanup EXIT

# The map check wants every occupied voxel on a trunk: the default config without range noise.
config="$logs/noiseless.yaml"
sed 's/range_noise_m: [0-9.]*/range_noise_m: 0.0/' "$here/../../../deploy/config/default.yaml" > "$config"
grep -q "range_noise_m: 0.0" "$config" || { echo "FAIL: no range_noise_m key in the default config"; exit 1; }

"$build/bin/mmh-sim" --lcm-url "$url" --config "$config" --realtime "${world[@]}" --duration 60 \
  > "$logs/sim.log" 2>&1 &
pids+=($!)
"$build/bin/mmh-mapping" --lcm-url "$url" > "$logs/mapping.log" 2>&1 &
pids+=($!)
"$build/bin/mmh-goal" --lcm-url "$url" --goal 19.95,0,1.5 --id 3 --rate-hz 2 --count 120 \
  > "$logs/goal.log" 2>&1 &
pids+=($!)

status=0
"$build/tests/mmh-test-mapcheck" --lcm-url "$url" "${world[@]}" --expect-goal 19.95,0,1.5 \
  --timeout 60 || status=$?
echo "--- mmh-sim"; cat "$logs/sim.log"
echo "--- mmh-mapping"; cat "$logs/mapping.log"
# Both services must still be running (no crash) when the check ends.
for pid in "${pids[@]:0:2}"; do
  kill -0 "$pid" 2>/dev/null || { echo "FAIL: a service exited early"; status=1; }
done
[ $status -eq 0 ] && echo "PASS" || echo "FAIL"
exit $status
