#!/usr/bin/env bash
# mmh-eam as a real process: LOCAL_MAP + PLAN_REQUEST_EAM in, PLAN_RESULT out, over udpm://
# inside a private network namespace (no traffic leaves the machine); then a clean stop.
set -euo pipefail
build=$1
here=$(cd "$(dirname "$0")" && pwd)
if [ "${MMH_IN_NETNS:-0}" != 1 ]; then exec "$here/../netns.sh" bash "$0" "$@"; fi

url="udpm://239.255.76.67:7667?ttl=0"
log=$(mktemp)
"$build/bin/mmh-eam" --lcm-url "$url" --prefix EAMT_ > "$log" 2>&1 &
eam=$!
status=0
"$build/tests/mmh-eam-request-check" --lcm-url "$url" --prefix EAMT_ || status=$?
kill -TERM "$eam" 2>/dev/null || true
eam_status=0
wait "$eam" || eam_status=$?
echo "--- mmh-eam log"
cat "$log"
rm -f "$log"
[ $status -eq 0 ] || { echo "FAIL: checks failed"; exit 1; }
[ $eam_status -eq 0 ] || { echo "FAIL: mmh-eam exited with $eam_status"; exit 1; }

# A bad configuration stops it at start-up with the key named.
bad=$(mktemp)
sed 's/^  knot_span_s: .*/  knot_span_s: -1/' "$here/../../../deploy/config/default.yaml" > "$bad"
out=$("$build/bin/mmh-eam" --lcm-url "$url" --config "$bad" 2>&1 || true)
rm -f "$bad"
echo "$out" | grep -q "eam.knot_span_s" || { echo "FAIL: no clear config error: $out"; exit 1; }
echo "PASS"
