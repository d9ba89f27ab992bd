#!/usr/bin/env bash
# Load scenario: one vehicle stack as separate processes over udpm:// (ttl=0) in a private network
# namespace, flying forests in real time while stress-ng competes for the CPU at the same
# priority. For every load, density and forest seed one flight; reports in OUT/report.md per
# (load, density): success, collisions, safe stops without arrival, mean flight time, the
# request-to-answer latency percentiles and how many decisions the arbiter took degraded (its
# latency budget above the configured one); the reaction time from a newly mapped danger to its
# answer committed, pooled over the flights of each load and density; then every flight.
#
#   tests/load/stress_flights.sh BUILD_DIR [--cpu 0,2,4] [--densities 0.1,0.2] [--seeds N]
#                                [--first-seed S] [--timeout S] [--out DIR]
#
# Exit code 0 when no flight collided, 1 otherwise (success may drop under load; a collision never
# may). Full size (docs/testing.md, "Load"): --cpu 0,2,4 --densities 0.1,0.2 --seeds 10.
set -euo pipefail
build=${1:?usage: stress_flights.sh BUILD_DIR [--cpu LIST] [--densities LIST] [--seeds N] [--out DIR]}
shift
root=$(cd "$(dirname "$0")/../.." && pwd)
if [ "${MMH_IN_NETNS:-0}" != 1 ]; then exec "$root/tests/integration/netns.sh" bash "$0" "$build" "$@"; fi
loads=0,2,4
densities=0.1,0.2
seeds=10
first_seed=1
timeout_s=90
out=""
while [ $# -gt 0 ]; do
  case "$1" in
    --cpu) loads=$2; shift 2 ;;
    --densities) densities=$2; shift 2 ;;
    --seeds) seeds=$2; shift 2 ;;
    --first-seed) first_seed=$2; shift 2 ;;
    --timeout) timeout_s=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    *) echo "stress_flights: unknown option $1" >&2; exit 2 ;;
  esac
done
command -v stress-ng >/dev/null || { echo "stress_flights: stress-ng is not installed (deploy/setup.sh installs it)" >&2; exit 2; }
temporary=0
[ -n "$out" ] || { out=$(mktemp -d /tmp/mmh-stress-XXXXXX); temporary=1; }
mkdir -p "$out"
export MMH_BIN_DIR=$build/bin
run="" stress="" logger=""
stop_flight() {
  if [ -n "$run" ]; then "$root/deploy/launch/stack.sh" stop --run-dir "$run" >/dev/null 2>&1 || true; fi
  if [ -n "$logger" ]; then kill -INT "$logger" 2>/dev/null || true; wait "$logger" 2>/dev/null || true; fi
  if [ -n "$stress" ]; then kill "$stress" 2>/dev/null || true; wait "$stress" 2>/dev/null || true; fi
  run="" stress="" logger=""
}
trap stop_flight EXIT

# One flight; appends "load density seed result time_s p50_ms p99_ms max_ms degraded" to flights.txt.
fly() {
  local load=$1 density=$2 seed=$3
  local dir=$out/cpu${load}-d${density}-s${seed}
  run=$dir
  mkdir -p "$dir"
  if [ "$load" -gt 0 ]; then stress-ng --cpu "$load" --quiet >/dev/null 2>&1 & stress=$!; fi
  # Everything but the point clouds: latencies, decisions, heartbeats and the maps to replay.
  lcm-logger -q -f -c '.*POINTCLOUD' -v "$dir/flight.lcm" & logger=$!
  "$root/deploy/launch/stack.sh" start --run-dir "$dir" \
    --sim-args "--world forest --density $density --seed $seed --realtime" \
    --goal 19.95,0,1.2 >/dev/null
  "$build/bin/mmh-mission-report" --timeout "$timeout_s" >"$dir/report.txt" 2>&1 || true
  stop_flight
  local result time_s
  case "$(sed -n 's/^mission: *//p' "$dir/report.txt")" in
    "goal reached") result=reached ;;
    COLLIDED) result=COLLIDED ;;
    *) result=stopped ;;
  esac
  time_s=$(sed -n 's/^flight time: *\([0-9.]*\) s/\1/p' "$dir/report.txt")
  "$build/bin/mmh-log-summary" "$dir/flight.lcm" >"$dir/summary.txt" 2>&1 || true
  # Worst mode's latency percentiles (columns: mode calls ok failed c50 / c99 / cmax l50 / l90 / l99 / lmax).
  local lat
  lat=$(awk '$1 ~ /^(FPM|SOM|EAM)$/ && NF >= 16 { if ($10 > p50) p50 = $10; if ($14 > p99) p99 = $14;
             if ($16 > mx) mx = $16 } END { printf "%.2f %.2f %.2f", p50, p99, mx }' "$dir/summary.txt")
  local degraded
  degraded=$(sed -n 's/^arbiter degraded: *\([0-9]*\).*/\1/p' "$dir/summary.txt")
  "$build/bin/mmh-log-summary" --reactions "$dir/flight.lcm" >>"$out/reactions-cpu$load-d$density.txt" 2>/dev/null || true
  echo "$load $density $seed $result ${time_s:-0} $lat ${degraded:-0}" >>"$out/flights.txt"
  echo "cpu $load density $density seed $seed: $result ${time_s:-?} s, latency p99 $(echo "$lat" | cut -d' ' -f2) ms"
}

IFS=, read -r -a load_list <<<"$loads"
IFS=, read -r -a density_list <<<"$densities"
# A report counts only this run's flights, also when OUT holds an earlier run.
: >"$out/flights.txt"
for load in "${load_list[@]}"; do
  for density in "${density_list[@]}"; do : >"$out/reactions-cpu$load-d$density.txt"; done
done
for load in "${load_list[@]}"; do
  for density in "${density_list[@]}"; do
    for seed in $(seq "$first_seed" $((first_seed + seeds - 1))); do fly "$load" "$density" "$seed"; done
  done
done

{
  echo "# One stack as processes in real time under stress-ng, $(nproc) cores"
  echo
  echo "| stress-ng --cpu | density | flights | reached | collisions | stopped safely | mean time (s) | latency p50 (ms) | latency p99 (ms) | latency max (ms) | degraded |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|"
  awk '{ k = $1 " " $2; n[k]++; if ($4 == "reached") { r[k]++; t[k] += $5 } else if ($4 == "COLLIDED") c[k]++; else s[k]++;
         p50[k] += $6; if ($7 > p99[k]) p99[k] = $7; if ($8 > mx[k]) mx[k] = $8; d[k] += $9; order[k] = NR }
       END { for (k in n) { split(k, f, " ");
         printf "| %s | %s | %d | %d | %d | %d | %s | %.2f | %.2f | %.2f | %d |\n", f[1], f[2], n[k], r[k], c[k], s[k],
           r[k] ? sprintf("%.2f", t[k] / r[k]) : "-", p50[k] / n[k], p99[k], mx[k], d[k] } }' \
    "$out/flights.txt" | sort -t'|' -k2,2n -k3,3n
  echo
  echo "(latency: request to answer, the worst mode of each flight; p50 averaged, p99 and max the worst flight's;"
  echo "degraded: decisions the arbiter took with its latency budget degraded, summed)"
  echo
  echo "Newly mapped danger on the committed trajectory -> the answer (a new trajectory or a stop) committed,"
  echo "from the scan that showed it to the ARBITER_STATUS received by the logger, all flights pooled:"
  echo
  echo "| stress-ng --cpu | density | reactions | p50 (ms) | p90 (ms) | p99 (ms) | max (ms) |"
  echo "|---|---|---|---|---|---|---|"
  for load in "${load_list[@]}"; do
    for density in "${density_list[@]}"; do
      sort -g "$out/reactions-cpu$load-d$density.txt" 2>/dev/null | awk -v l="$load" -v d="$density" '
        { v[NR] = $1 }
        function at(q,  i, lo) { i = q * (NR - 1); lo = int(i); return v[lo + 1] + (v[lo + (lo + 1 < NR ? 2 : 1)] - v[lo + 1]) * (i - lo) }
        END { if (NR == 0) printf "| %s | %s | 0 | - | - | - | - |\n", l, d;
              else printf "| %s | %s | %d | %.1f | %.1f | %.1f | %.1f |\n", l, d, NR, at(0.5), at(0.9), at(0.99), v[NR] }'
    done
  done
  echo
  echo '```'
  echo "cpu density seed result time_s p50_ms p99_ms max_ms degraded"
  cat "$out/flights.txt"
  echo '```'
} >"$out/report.md"
cat "$out/report.md"
if grep -q COLLIDED "$out/flights.txt"; then echo "FAIL: a flight collided (report: $out/report.md)"; exit 1; fi
echo "PASS: no collision"
if [ $temporary = 1 ]; then rm -rf "$out"; else echo "report: $out/report.md"; fi
