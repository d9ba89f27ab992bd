#!/usr/bin/env bash
# Bad input at the real processes, in a private network namespace: mmh-bad-input publishes its
# catalogue (NaN/Inf fields, lengths that disagree with the data, wrong types, truncated and random
# buffers, time going back, absurd sizes and times, an empty scan and one of two million points,
# goals outside the geofence or inside an obstacle, targets outside it) at mapping, awareness, FPM,
# SOM, EAM and the arbiter, then at mmh-sim; every service must stay up and count each one in
# HEARTBEAT. Then every executable is started with corrupt configuration files: each must refuse
# to start with exit code 1 and a message naming the problem, never crash.
set -euo pipefail
build=$1
root=$(cd "$(dirname "$0")/../../.." && pwd)
if [ "${MMH_IN_NETNS:-0}" != 1 ]; then exec "$root/tests/integration/netns.sh" bash "$0" "$@"; fi
run=$(mktemp -d)
export MMH_BIN_DIR=$build/bin MMH_RUN_DIR=$run
launch=$root/deploy/launch
cleanup() {
  "$launch/stack.sh" stop >/dev/null 2>&1 || true
  "$launch/sim.sh" stop --prefix SIM_ >/dev/null 2>&1 || true
}
trap 'cleanup; [ -n "${MMH_KEEP_RUN:-}" ] || rm -rf "$run"' EXIT
fail() {
  echo "FAIL: $*"
  for f in "$run"/*.log; do [ -f "$f" ] && { echo "== $f"; tail -5 "$f"; }; done
  exit 1
}

# 1. The planning stack (no simulator: nothing else publishes, so only the catalogue arrives).
# UDP cannot carry a scan of millions of points here (the kernel's receive buffer drops its
# fragments; tests/unit/mapping sends two million through memq://), so mapping.max_points is
# lowered to 50,000 and the oversized scan has 120,000 points (1.4 MB), with a 4 MB receive
# buffer (this kernel's net.core.rmem_max) so that the kernel keeps all of its fragments.
export LCM_DEFAULT_URL='udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304'
sed 's/^\(  max_points:\).*/\1 50000/' "$root/deploy/config/default.yaml" >"$run/config.yaml"
export MMH_CONFIG=$run/config.yaml
"$launch/stack.sh" start >/dev/null
"$build/bin/mmh-bad-input" --target stack --huge-scan-points 120000 --mapping-max-points 50000 ||
  fail "the stack did not survive or count its bad input"
unset MMH_CONFIG LCM_DEFAULT_URL
"$launch/stack.sh" status | grep -v "mmh-sim\|mmh-goal" | grep -q stopped && fail "a service died"
grep -h "rejected\|refused\|scan_" "$run"/*.log | tail -n 12 || true

# 2. The simulator (TRAJECTORY and GOAL), under its own prefix.
"$launch/sim.sh" start --prefix SIM_ -- --world forest --density 0.05 --seed 5 --realtime >/dev/null
"$build/bin/mmh-bad-input" --target sim --prefix SIM_ || fail "mmh-sim did not survive or count"
"$launch/sim.sh" status --prefix SIM_ >/dev/null || fail "mmh-sim died"
cleanup

# 3. Corrupt configuration files: refused at start-up with the reason, exit code 1.
default=$root/deploy/config/default.yaml
printf 'vehicle: [1, 2\n  max_vel_mps: {{\n' >"$run/truncated.yaml"
awk 'BEGIN { srand(7); for (i = 0; i < 3000; i++) printf "%c", 1 + int(rand() * 254) }' >"$run/random.yaml"
for exe in mmh-mapping mmh-awareness mmh-fpm mmh-som mmh-eam mmh-arbiter mmh-sim; do
  # A key this service reads, spoilt four ways.
  case $exe in
    mmh-mapping) key=map.resolution_m ;;
    mmh-awareness) key=awareness.sensor_range_m ;;
    *) key=vehicle.max_vel_mps ;;
  esac
  name=${key#*.}
  sed "s/^\(  $name:\).*/\1 .nan/" "$default" >"$run/nan.yaml"
  sed "s/^\(  $name:\).*/\1 -2.0/" "$default" >"$run/negative.yaml"
  sed "s/^\(  $name:\).*/\1 \"fast\"/" "$default" >"$run/text.yaml"
  grep -v "^  $name:" "$default" >"$run/missing.yaml"
  for cfg in truncated random negative text missing absent nan; do
    code=0
    timeout 20 "$build/bin/$exe" --config "$run/$cfg.yaml" >"$run/out.txt" 2>&1 || code=$?
    if [ $code -ne 1 ]; then
      cat "$run/out.txt"
      fail "$exe with the $cfg config exited with $code (expected 1: refused)"
    fi
    case $cfg in
      truncated) pattern="not valid YAML" ;;
      random) pattern="not valid YAML|top level must be a mapping|is missing" ;;
      nan | negative | text) pattern="'$key'" ;;
      missing) pattern="'$key' is missing" ;;
      absent) pattern="cannot open" ;;
    esac
    grep -Eq "$pattern" "$run/out.txt" || { cat "$run/out.txt"; fail "$exe, $cfg config: no reason"; }
  done
  echo "$exe refuses corrupt configuration files, e.g. $(head -c 160 "$run/out.txt")"
done
echo PASS
