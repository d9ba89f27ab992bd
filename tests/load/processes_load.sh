#!/usr/bin/env bash
# Load test: N vehicles (default 5), each a whole stack of separate processes (mapping,
# awareness, FPM, SOM, EAM, arbiter, sim in real time, goal publisher) with its own --prefix
# UAV<i>_, all on LCM's default udpm:// URL (ttl=0) inside one private network namespace, for
# --duration wall seconds. Reports, in OUT/report.md:
#   - per service of every vehicle: peak RSS (VmHWM) and resident size (VmRSS) at 1/3 of the run
#     and at the end (growth check: end <= 1.25 x third + 16 MB);
#   - that no service died;
#   - per vehicle, from an lcm-logger log of the small channels (mmh-log-summary): planning
#     calls, compute time and request-to-result latency p50/p90/p99/max, mission result.
#
#   tests/load/processes_load.sh BUILD_DIR [--vehicles N] [--duration S] [--out DIR]
# Exit code 0 when no service died and none grew beyond the bound, 1 otherwise.
set -euo pipefail
build=${1:?usage: processes_load.sh BUILD_DIR [--vehicles N] [--duration S] [--out DIR]}
shift
root=$(cd "$(dirname "$0")/../.." && pwd)
if [ "${MMH_IN_NETNS:-0}" != 1 ]; then exec "$root/tests/integration/netns.sh" bash "$0" "$build" "$@"; fi
vehicles=5
duration=60
out=""
while [ $# -gt 0 ]; do
  case "$1" in
    --vehicles) vehicles=$2; shift 2 ;;
    --duration) duration=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    *) echo "processes_load: unknown option $1" >&2; exit 2 ;;
  esac
done
[ -n "$out" ] || out=$(mktemp -d /tmp/mmh-load-XXXXXX)
mkdir -p "$out"
run=$out/run
mkdir -p "$run"
export MMH_BIN_DIR=$build/bin
services=(mmh-mapping mmh-awareness mmh-fpm mmh-som mmh-eam mmh-arbiter mmh-sim)
logger_pid=""
cleanup() {
  for i in $(seq 1 "$vehicles"); do
    "$root/deploy/launch/stack.sh" stop --run-dir "$run" --prefix "UAV${i}_" >/dev/null 2>&1 || true
  done
  if [ -n "$logger_pid" ]; then kill "$logger_pid" 2>/dev/null || true; wait "$logger_pid" 2>/dev/null || true; fi
}
trap cleanup EXIT

# The small channels only (no POINTCLOUD, LOCAL_MAP): enough for latencies and results.
lcm-logger -q -f -c '.*(POINTCLOUD|LOCAL_MAP)' -v "$out/load.lcm" &
logger_pid=$!
for i in $(seq 1 "$vehicles"); do
  "$root/deploy/launch/stack.sh" start --run-dir "$run" --prefix "UAV${i}_" \
    --sim-args "--world forest --density 0.1 --seed $((6 + i)) --realtime" --goal 19.95,0,1.2 >/dev/null
done

# VmRSS / VmHWM in kB of a pid (0 if gone).
mem() { awk -v f="$2:" '$1 == f { print $2 }' "/proc/$1/status" 2>/dev/null || echo 0; }
pid_of() { cat "$run/$1.pid" 2>/dev/null || echo 0; }

third=$((duration / 3))
sleep "$third"
declare -A rss_third
for i in $(seq 1 "$vehicles"); do
  for s in "${services[@]}"; do rss_third[UAV${i}_$s]=$(mem "$(pid_of "UAV${i}_$s")" VmRSS); done
done
sleep $((duration - third))

status=0
{
  echo "# Load: $vehicles vehicles as separate processes, ${duration} s, $(nproc) cores"
  echo
  echo "load average at the end: $(cut -d' ' -f1-3 /proc/loadavg)"
  echo
  echo "| vehicle | service | alive | peak RSS MB | RSS at ${third} s MB | RSS at ${duration} s MB |"
  echo "|---|---|---|---|---|---|"
} >"$out/report.md"
for i in $(seq 1 "$vehicles"); do
  for s in "${services[@]}"; do
    tag=UAV${i}_$s
    pid=$(pid_of "$tag")
    alive=yes
    if [ "$pid" = 0 ] || ! kill -0 "$pid" 2>/dev/null; then alive=NO; status=1; fi
    hwm=$(mem "$pid" VmHWM)
    rss=$(mem "$pid" VmRSS)
    early=${rss_third[$tag]:-0}
    if [ "$rss" -gt $((early * 5 / 4 + 16384)) ]; then alive="$alive, GREW"; status=1; fi
    awk -v v="UAV${i}_" -v s="$s" -v a="$alive" -v h="$hwm" -v e="$early" -v r="$rss" \
      'BEGIN { printf "| %s | %s | %s | %.1f | %.1f | %.1f |\n", v, s, a, h / 1024, e / 1024, r / 1024 }' \
      >>"$out/report.md"
  done
done
cleanup
logger_pid=""
{
  echo
  echo '```'
  "$build/bin/mmh-log-summary" "$out/load.lcm" | grep -E "^== vehicle|^planning|^(FPM|SOM|EAM|STOP) |^total planning|^mission" || true
  echo '```'
} >>"$out/report.md"
cat "$out/report.md"
[ $status = 0 ] && echo "PASS (report: $out/report.md)" || echo "FAIL (report: $out/report.md)"
exit $status
