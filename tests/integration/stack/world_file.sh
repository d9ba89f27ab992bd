#!/usr/bin/env bash
# Worlds as files (lock-step, deterministic): a forest written with mmh-sim --export-world (and
# mmh-stack --export-world, the same bytes) is flown back with mmh-stack --world FILE.pcd and
# reaches the goal, and so is an ego-forest; a goal outside the file's bounds stops mmh-stack,
# mmh-bench and mmh-sim at once with the coordinates and the bounds; --fit-geofence fits the
# fence to the file.
set -euo pipefail
build=$1
fail() { echo "FAIL: $*"; exit 1; }
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
world=(--size 20,20,3 --density 0.1 --seed 3 --start=-8,0,1.2 --goal 8,0,1.2)

"$build/bin/mmh-sim" "${world[@]}" --export-world "$dir/forest.pcd" || fail "mmh-sim --export-world"
"$build/bin/mmh-stack" "${world[@]}" --export-world "$dir/forest2.pcd" || fail "mmh-stack --export-world"
cmp -s "$dir/forest.pcd" "$dir/forest2.pcd" || fail "mmh-sim and mmh-stack wrote different worlds"
head -c 400 "$dir/forest.pcd" | grep -q "^DATA binary" || fail "not a binary PCD"

json=$("$build/bin/mmh-stack" --log-level error --json --world "$dir/forest.pcd" \
  --start=-8,0,1.2 --goal 8,0,1.2) || fail "the exported forest was not flown: $json"
echo "$json"
grep -q '"result": "reached"' <<< "$json" || fail "the exported forest: not reached"

# EGO-Planner's forest (ragged pillars, rings) exported the same way is flown back too.
"$build/bin/mmh-stack" --world ego-forest --size 20,20,3 --density 0.19 --seed 3 \
  --start=-8,0,1.2 --goal 8,0,1.2 --export-world "$dir/ego.pcd" || fail "ego-forest export"
json=$("$build/bin/mmh-stack" --log-level error --json --world "$dir/ego.pcd" \
  --start=-8,0,1.2 --goal 8,0,1.2) || fail "the exported ego-forest was not flown: $json"
grep -q '"result": "reached"' <<< "$json" || fail "the exported ego-forest: not reached"

# Outside the world's bounds (x within the geofence): refused at once, naming both.
check_refused() {
  local tool=$1 expect=$2
  shift 2
  local out status=0
  out=$("$build/bin/$tool" --log-level error "$@" 2>&1) || status=$?
  [ $status -ne 0 ] || fail "$tool $* did not fail"
  grep -qF -- "$expect" <<< "$out" || fail "$tool $*: '$out' lacks '$expect'"
  echo "refused as expected: $out"
}
bounds="the goal [15, 0, 1.2] lies outside the world's bounds (x = 15 > "
check_refused mmh-stack "$bounds" --world "$dir/forest.pcd" --start=-8,0,1.2 --goal 15,0,1.2
check_refused mmh-stack "spans x [" --world "$dir/forest.pcd" --start=-8,0,1.2 --goal 15,0,1.2
check_refused mmh-sim "$bounds" --world "$dir/forest.pcd" --start=-8,0,1.2 --goal 15,0,1.2 \
  --lcm-url memq://
status=0
out=$("$build/bin/mmh-bench" --world "$dir/forest.pcd" --start=-8,0,1.2 --goal 15,0,1.2 \
  --methods mmh --trials 1 --no-plots --out "$dir/bench" 2>&1) || status=$?
[ $status -eq 2 ] || fail "mmh-bench accepted a goal outside the world (exit $status): $out"
grep -qF "$bounds" <<< "$out" || fail "mmh-bench: $out"
[ ! -e "$dir/bench/results.json" ] || fail "mmh-bench flew before refusing"
echo "refused as expected: $out"

# --fit-geofence: the fence is the file's bounds plus 1 m; the goal at x = 15 is now outside the
# fence (named with the fitted keys), and one inside flies.
check_refused mmh-stack "geofence.max_m = [11.22," --world "$dir/forest.pcd" --fit-geofence \
  --start=-8,0,1.2 --goal 15,0,1.2
out=$("$build/bin/mmh-stack" --log-level error --json --world "$dir/forest.pcd" --fit-geofence \
  --start=-8,0,1.2 --goal 8,0,1.2 2>"$dir/err") || fail "fitted fence: $out $(cat "$dir/err")"
grep -qF -- "--fit-geofence: geofence.min_m = [" "$dir/err" || fail "the fitted fence not printed"
grep -q '"result": "reached"' <<< "$out" || fail "fitted fence: not reached: $out"
echo PASS
