#!/usr/bin/env bash
# mmh-bench with a tiny protocol in the EGO-Planner forest (1 map x 1 trial, one density, LiDAR,
# one --set): the census of stops and stalls is in summary.md, on stdout and in results.json;
# where the time goes per mode is in summary.md and results.json;
# mmh-stack --json ends with the census fields; an unknown --set key is refused by name.
# mmh-bench-compare pairs that run with itself (no change) and refuses runs without common flights.
set -euo pipefail
build=$1
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

"$build/bin/mmh-bench" --methods mmh --densities 0.2 --maps 1 --trials 1 --world ego-forest \
  --size 30,20,3 --start -12,0,1.2 --goal 12,0,1.2 --sensor lidar --set sim.lidar.range_noise_m=0.01 \
  --no-plots --out "$out/bench" >"$out/stdout" 2>"$out/stderr" || { cat "$out/stderr"; fail "mmh-bench failed"; }
cat "$out/stdout"
for where in "$out/stdout" "$out/bench/summary.md"; do
  grep -q "## Stops and stalls" "$where" || fail "no census section in $where"
  grep -q "| density | method | flights | stops | to rest | held (s) | stops / flight | causes | failed modes at the stops | max calls w/o commit | longest no progress (s) |" "$where" \
    || fail "census columns missing in $where"
  grep -qE "^\| 0\.20 \| mmh \| 1 \| [0-9]+ \|" "$where" || fail "no census row in $where"
done
python3 - "$out/bench/results.json" <<'PY' || fail "results.json lacks the census"
import json, sys
r = json.load(open(sys.argv[1]))[0]
assert r["error"] == "", r["error"]
assert r["world"] == "ego-forest" and r["sensor"] == "lidar" and r["size"] == [30, 20, 3], r
for key in ("stop_causes", "stop_events", "max_calls_without_commit", "longest_no_progress_s"):
    assert key in r, key
assert sum(r["stop_causes"].values()) == len(r["stop_events"])
for s in r["stop_events"]:
    assert {"time_s", "trigger", "cause", "detail", "failed_modes", "held_s",
            "lowest_speed_mps"} <= set(s), s
    assert s["held_s"] >= 0 and s["time_s"] + s["held_s"] <= r["flight_time_s"] + 0.5, s
    assert 0 <= s["lowest_speed_mps"] <= 3.2, s
# Where the time goes: every mode slot, adding up to the flight's time.
for key in ("time_by_mode_s", "time_lost_by_mode_s"):
    assert set(r[key]) == {"none", "fpm", "som", "eam", "stop"}, r[key]
total = sum(r["time_by_mode_s"].values())
assert abs(total - r["flight_time_s"]) < 0.2, (total, r["flight_time_s"])
assert 0 <= sum(r["time_lost_by_mode_s"].values()) <= total
PY
grep -qE "^\| 0\.20 \| mmh \| 1 \| [0-9.]+ \([0-9.]+\) \|" "$out/bench/summary.md" \
  || fail "no row in summary.md's 'Where the time goes'"


compare="$build/bin/mmh-bench-compare"
"$compare" "$out/bench" "$out/bench/results.json" --out "$out/compare.md" || fail "mmh-bench-compare failed"
cat "$out/compare.md"
grep -qE "^\| ego-forest \| 0\.20 \| mmh \| 1 \| 1 → 1 \| 0 → 0 \| ([0-9]+) → \1 \| .* \| \+0\.000 \| \[\+0\.000, \+0\.000\] \| 0 / 0 \|" "$out/compare.md" \
  || fail "a run compared with itself does not show an unchanged row"
echo '[]' >"$out/empty.json"
if "$compare" "$out/bench" "$out/empty.json" 2>"$out/compare.err"; then
  fail "mmh-bench-compare accepted runs without a common flight"
fi
grep -q "no flight in common" "$out/compare.err" || fail "unclear error: $(cat "$out/compare.err")"
if "$compare" "$out/bench" "$out/missing" 2>"$out/compare.err"; then
  fail "mmh-bench-compare accepted a missing run"
fi
grep -q "cannot read" "$out/compare.err" || fail "unclear error: $(cat "$out/compare.err")"

if "$build/bin/mmh-bench" --methods mmh --densities 0 --maps 1 --trials 1 --no-plots \
     --set vehicle.no_such_key=1 --out "$out/bad" 2>"$out/bad.err"; then
  fail "mmh-bench accepted an unknown --set key"
fi
grep -q "vehicle.no_such_key" "$out/bad.err" || fail "the error does not name the key: $(cat "$out/bad.err")"
if "$build/bin/mmh-stack" --set vehicle.no_such_key=1 --json 2>"$out/stack.err"; then
  fail "mmh-stack accepted an unknown --set key"
fi
grep -q "vehicle.no_such_key" "$out/stack.err" || fail "mmh-stack's error does not name the key"

json=$("$build/bin/mmh-stack" --density 0.05 --seed 7 --log-level error --json) || true
echo "$json"
echo "$json" | grep -qE '"wall_time_s": [0-9.e+-]+, "stop_causes": \{[^}]*\}, "max_calls_without_commit": [0-9]+, "longest_no_progress_s": [0-9.e+-]+, "trajectory_digest": "[0-9a-f]+"\}$' \
  || fail "mmh-stack --json does not end with the census fields"
echo PASS
