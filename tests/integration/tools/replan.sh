#!/usr/bin/env bash
# mmh-replan: the EAM, SOM and FPM requests of lock-step flights recorded by mmh-stack --log, planned
# again by the same build and configuration, fail exactly where they failed in flight (nothing
# fixed, nothing broken, one --list line per failure, one --answers line per answer); another configuration is accepted with
# --set; --trace prints the rounds of one EAM request; usage errors exit with 2 and say why.
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
check_usage --set eam.no_such_key=1 "$log"
check_usage --trace x1 "$log"
check_usage --mode som --trace 1 "$log"
check_usage --mode fpm --trace 1 "$fpm_log"
echo "mmh-replan: OK"
