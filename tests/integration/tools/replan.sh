#!/usr/bin/env bash
# mmh-replan: the EAM, SOM and FPM requests of lock-step flights recorded by mmh-stack --log, planned
# again by the same build and configuration, fail exactly where they failed in flight (nothing
# fixed, nothing broken, one --list line per failure, one --answers line per answer); another configuration is accepted with
# --set; --trace prints the rounds of one EAM request; --samples prints one request's path and
# answer (or the trajectory the mode refused) in time; usage errors exit with 2 and say why.
set -euo pipefail
build=$1
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
replan=$build/bin/mmh-replan
fail() { echo "FAIL: $*"; exit 1; }

log=$out/flight.lcm
# A 0.2 obs/m² forest whose flight asks EAM 12 times, 2 of them failing.
"$build/bin/mmh-stack" --density 0.2 --seed 1300 --noise-seed 130004 --log-level error --json \
  --log "$log" > "$out/flight.json" || fail "flight failed"

for mode in eam som; do
  "$replan" --mode "$mode" "$log" > "$out/$mode.txt" || fail "mmh-replan --mode $mode exit $?"
  cat "$out/$mode.txt"
  requests=$(sed -nE 's/^requests ([0-9]+) .*/\1/p' "$out/$mode.txt")
  [ "${requests:-0}" -ge 1 ] || fail "$mode: no request found in the log"
  line=$(grep -E '^failed then ' "$out/$mode.txt") || fail "$mode: no summary line"
  then_=$(sed -nE 's/^failed then ([0-9]+), now ([0-9]+): ([0-9]+) fixed, ([0-9]+) broken/\1 \2 \3 \4/p' \
    "$out/$mode.txt")
  read -r before now fixed broken <<< "$then_"
  [ "$before" = "$now" ] && [ "$fixed" = 0 ] && [ "$broken" = 0 ] ||
    fail "$mode: the same build planned differently: $line"
  "$replan" --mode "$mode" --list "$log" > "$out/$mode.list" || fail "$mode: --list exit $?"
  listed=$(grep -c "^$log " "$out/$mode.list" || true)
  [ "$listed" = "$before" ] || fail "$mode: --list shows $listed requests, $before failed"
  with_state=$(grep -cE "^$log .* [0-9.]+ m/s  [0-9.]+ m/s\^2  then: " "$out/$mode.list" || true)
  [ "$with_state" = "$listed" ] || fail "$mode: --list lines without the start speed and acceleration"
  # --answers: one line per request answered now, each with a positive duration and length.
  "$replan" --mode "$mode" --answers "$log" > "$out/$mode.answers" || fail "$mode: --answers exit $?"
  answered=$(grep -cE "^$log .* target [0-9.]+ m away: [0-9.]+ s, [0-9.]+ m, mean [0-9.]+ m/s" \
    "$out/$mode.answers" || true)
  [ "$answered" = "$((requests - now))" ] ||
    fail "$mode: --answers shows $answered answers, $((requests - now)) were answered"
  zero=$(grep -cE "^$log .* away: 0\.00 s" "$out/$mode.answers" || true)
  [ "$zero" = 0 ] || fail "$mode: --answers shows answers without duration"
  grep -qE '^answers now: [0-9.]+ m in [0-9.]+ s \(mean speed [0-9.]+ m/s\)' "$out/$mode.txt" ||
    fail "$mode: no 'answers now' line in the summary"
done
# FPM needs no map: the FPM requests of a sparse forest's flight, planned again the same.
fpm_log=$out/sparse.lcm
"$build/bin/mmh-stack" --density 0.05 --seed 1100 --noise-seed 110001 --log-level error --json \
  --log "$fpm_log" > "$out/sparse.json" || fail "sparse flight failed"
"$replan" --mode fpm "$fpm_log" > "$out/fpm.txt" || fail "mmh-replan --mode fpm exit $?"
cat "$out/fpm.txt"
fpm_requests=$(sed -nE 's/^requests ([0-9]+) .*/\1/p' "$out/fpm.txt")
[ "${fpm_requests:-0}" -ge 1 ] || fail "fpm: no FPM request found in the sparse flight"
grep -qE '^failed then 0, now 0: 0 fixed, 0 broken' "$out/fpm.txt" ||
  fail "fpm: the same build planned differently: $(grep '^failed then' "$out/fpm.txt")"

before=$(sed -nE 's/^failed then ([0-9]+),.*/\1/p' "$out/eam.txt")
[ "$before" -ge 1 ] || fail "the flight had no EAM failure to replan"

# --trace shows the rounds of one failed EAM request, and only of that one.
failed_id=$("$replan" --list "$log" | sed -nE 's/.* request ([0-9]+) .*/\1/p' | head -1)
"$replan" --trace "$failed_id" "$log" > "$out/trace.txt" || fail "--trace exit $?"
rounds=$(grep -cE '^  round [0-9]+: stretches [0-9]+, pairs added' "$out/trace.txt" || true)
[ "$rounds" -ge 1 ] || fail "--trace $failed_id printed no round"
"$replan" --trace 999999 "$log" > "$out/notrace.txt" || fail "--trace of no request exit $?"
! grep -q '^  round ' "$out/notrace.txt" || fail "--trace of an unknown id printed rounds"

# --samples: the request, the path the mode searched and the trajectory it refused (or its
# answer), one row per 0.05 s: t, x, y, z, speed, acceleration, jerk.
som_refused=$("$replan" --mode som --list "$log" |
  sed -nE 's/.* request ([0-9]+) .* now: verification: max .*/\1/p' | head -1)
[ -n "$som_refused" ] || fail "the flight had no SOM answer refused by its verification"
"$replan" --mode som --samples "$som_refused" "$log" > "$out/refused.txt" ||
  fail "--samples exit $?"
grep -qE "^request $som_refused at [0-9.]+ s \(som\): start \(" "$out/refused.txt" ||
  fail "--samples $som_refused: no request line"
grep -qE '^now: failed: verification: max ' "$out/refused.txt" || fail "--samples: no failure line"
grep -qE '^A\* path \([0-9]+ points\):' "$out/refused.txt" || fail "--samples: no A* path"
grep -qE "^the trajectory SOM's verification refused: [0-9]+ pieces" "$out/refused.txt" ||
  fail "--samples: the refused trajectory is not shown"
sample_row='^ +-?[0-9]+\.[0-9]{2}( +-?[0-9]+\.[0-9]{2}){6}$'
rows=$(grep -cE "$sample_row" "$out/refused.txt" || true)
[ "$rows" -ge 10 ] || fail "--samples printed $rows sample rows of the refused trajectory"
# The samples show what the verification refused: a speed over 3 m/s or an acceleration over
# 2 m/s^2 (the vehicle's limits) somewhere.
grep -E "$sample_row" "$out/refused.txt" | awk '$5 > 3.0 || $6 > 2.0 {over = 1} END {exit !over}' ||
  fail "--samples: no sample of the refused trajectory over the limits"
# An answered request: its answer, ending at rest.
som_ok=$("$replan" --mode som --answers "$log" | sed -nE 's/.* request ([0-9]+) .*/\1/p' | head -1)
"$replan" --mode som --samples "$som_ok" "$log" > "$out/answer.txt" || fail "--samples exit $?"
grep -qE '^now: answered' "$out/answer.txt" || fail "--samples $som_ok: not answered"
grep -qE '^answer: [0-9]+ pieces' "$out/answer.txt" || fail "--samples $som_ok: no answer line"
last_speed=$(grep -E "$sample_row" "$out/answer.txt" | tail -1 | awk '{print $5}')
[ "$last_speed" = "0.00" ] || fail "--samples $som_ok: the answer ends at $last_speed m/s"
# EAM: a failed request shows its last curve.
eam_failed=$("$replan" --list "$log" | sed -nE 's/.* request ([0-9]+) .*/\1/p' | head -1)
"$replan" --samples "$eam_failed" "$log" > "$out/eam_samples.txt" || fail "--samples exit $?"
grep -qE "^EAM's last curve \(not verified\): [0-9]+ pieces" "$out/eam_samples.txt" ||
  fail "--samples $eam_failed: EAM's last curve is not shown"

# Another configuration of the mode: planned and summarised (whatever it changes).
"$replan" --set eam.max_rebound_rounds=2 "$log" > "$out/rounds.txt" || fail "--set exit $?"
grep -qE '^failed then [0-9]+, now [0-9]+' "$out/rounds.txt" || fail "--set gave no summary"

# Usage errors: exit code 2 with a message.
check_usage() {
  local status=0
  "$replan" "$@" > /dev/null 2> "$out/err.txt" || status=$?
  [ $status -eq 2 ] || fail "'$*' gave exit code $status, not 2"
  [ -s "$out/err.txt" ] || fail "'$*' said nothing"
}
check_usage
check_usage "$out/missing.lcm"
check_usage --mode xyz "$log"
check_usage --samples abc "$log"
check_usage --set eam.no_such_key=1 "$log"
check_usage --trace x1 "$log"
check_usage --mode som --trace 1 "$log"
check_usage --mode fpm --trace 1 "$fpm_log"
echo "mmh-replan: OK"
