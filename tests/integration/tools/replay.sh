#!/usr/bin/env bash
# mmh-replay: a lock-step flight recorded by mmh-stack --log replays with the same decisions
# (with and without a channel prefix); another policy makes it report a divergence (exit code 0,
# 3 with --strict); usage errors exit with 2.
set -euo pipefail
build=$1
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
replay=$build/bin/mmh-replay
flight=(--density 0.1 --seed 7 --start=-6,0,1.2 --goal 6,0,1.2 --log-level error --json)

fail() { echo "FAIL: $*"; exit 1; }
# The share of recorded decisions that matched, from the report's "matched:" line.
matched_percent() { sed -nE 's/^matched: +[0-9]+ \(([0-9.]+) %.*/\1/p' "$1"; }

for prefix in "" UAV1_; do
  log=$out/flight${prefix}.lcm
  "$build/bin/mmh-stack" "${flight[@]}" --prefix "$prefix" --log "$log" || fail "flight failed"
  "$replay" "$log" > "$out/report.txt" || fail "mmh-replay exit code $?"
  cat "$out/report.txt"
  for line in "log:" "inputs:" "decisions:" "matched:" "differed:" "commits:" "first divergence:"; do
    grep -q "^$line" "$out/report.txt" || fail "report has no '$line' line"
  done
  grep -q "prefix \"$prefix\"" "$out/report.txt" || fail "prefix \"$prefix\" not detected"
  grep -qE '^decisions: +recorded [1-9]' "$out/report.txt" || fail "no recorded decisions"
  pct=$(matched_percent "$out/report.txt")
  awk -v p="$pct" 'BEGIN { exit !(p >= 90) }' || fail "only $pct % of the decisions matched"
done

# Another policy decides differently: reported, exit code 0; --strict makes it 3.
"$replay" "$out/flight.lcm" --policy ego --list > "$out/ego.txt" || fail "exit code $? with ego"
grep -q "^first divergence: decision" "$out/ego.txt" || { cat "$out/ego.txt"; fail "no divergence"; }
grep -qE '^  [-+] #' "$out/ego.txt" || fail "--list shows no differing decision"
status=0
"$replay" "$out/flight.lcm" --policy ego --strict > /dev/null || status=$?
[ $status -eq 3 ] || fail "--strict with a divergence gave exit code $status, not 3"

# Usage errors: exit code 2 with a message.
for args in "" "$out/missing.lcm" "--bogus $out/flight.lcm" "$out/flight.lcm --config $out/none.yaml"; do
  status=0
  # shellcheck disable=SC2086
  "$replay" $args > /dev/null 2> "$out/err.txt" || status=$?
  [ $status -eq 2 ] || fail "'mmh-replay $args' exit code $status, not 2"
  [ -s "$out/err.txt" ] || fail "'mmh-replay $args' printed no error"
done
echo PASS
