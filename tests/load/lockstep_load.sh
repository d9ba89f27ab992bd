#!/usr/bin/env bash
# Load test: N vehicles (default 10), each a whole prefixed stack (UAV1_ ... UAVN_) with its own
# forest, in one lock-step simulation in one process (mmh-stack --vehicles N). Passes when the
# process does not crash (exit 0 or 3: every vehicle reached, or some did not) and its resident
# size stops growing (last sample <= 1.25 x the sample at a third of the run + 16 MB). Prints the
# JSON of mmh-stack: per vehicle result and compute times, compute p50/p90/p99 of all planning
# calls, resident size every 10 simulated s, peak RSS (VmHWM).
#
#   tests/load/lockstep_load.sh BUILD_DIR [--vehicles N] [--timeout S] [--density D]
set -euo pipefail
build=${1:?usage: lockstep_load.sh BUILD_DIR [--vehicles N] [--timeout S] [--density D]}
shift
vehicles=10
timeout=60
density=0.1
while [ $# -gt 0 ]; do
  case "$1" in
    --vehicles) vehicles=$2; shift 2 ;;
    --timeout) timeout=$2; shift 2 ;;
    --density) density=$2; shift 2 ;;
    *) echo "lockstep_load: unknown option $1" >&2; exit 2 ;;
  esac
done
status=0
json=$("$build/bin/mmh-stack" --vehicles "$vehicles" --density "$density" --seed 7 \
  --timeout "$timeout" --json --log-level error) || status=$?
echo "$json"
if [ $status -ne 0 ] && [ $status -ne 3 ]; then echo "FAIL: mmh-stack exited with $status"; exit 1; fi
python3 - "$json" "$vehicles" <<'PY'
import json, sys
r = json.loads(sys.argv[1])
n = int(sys.argv[2])
assert len(r["vehicles"]) == n, "one record per vehicle"
rss = r["rss_mb"]
third = rss[len(rss) // 3]
print(f"vehicles reached: {r['succeeded']} of {n}; planning compute p50 {r['compute_ms_p50']:.2f} ms,"
      f" p90 {r['compute_ms_p90']:.2f} ms, p99 {r['compute_ms_p99']:.2f} ms;"
      f" RSS {third:.0f} MB at a third, {rss[-1]:.0f} MB at the end, peak {r['peak_rss_mb']:.0f} MB;"
      f" wall {r['wall_time_s']:.1f} s")
if rss[-1] > 1.25 * third + 16:
    sys.exit("FAIL: resident size kept growing")
PY
echo PASS
