#!/usr/bin/env bash
# The real mmh-som process over udpm:// in a private network namespace: a LOCAL_MAP and plan
# requests in (mmh-som-test-client), a verified trajectory and a refusal with its reason out.
set -euo pipefail
build=$1
here=$(cd "$(dirname "$0")" && pwd)
if [ "${MMH_IN_NETNS:-0}" != 1 ]; then exec "$here/../netns.sh" bash "$0" "$@"; fi

url="udpm://239.255.76.67:7667?ttl=0"
log=$(mktemp)
"$build/bin/mmh-som" --lcm-url "$url" --prefix SOMT_ > "$log" 2>&1 &
som=$!
cleanup() { kill "$som" 2>/dev/null || true; rm -f "$log"; }
trap cleanup EXIT

status=0
"$build/tests/mmh-som-test-client" --lcm-url "$url" --prefix SOMT_ --timeout 60 || status=$?

# mmh-som stops cleanly on SIGTERM.
kill -TERM "$som"
som_status=0
wait "$som" || som_status=$?
echo "--- mmh-som log"; cat "$log"
[ $status -eq 0 ] || { echo "FAIL: client checks failed"; exit 1; }
[ $som_status -eq 0 ] || { echo "FAIL: mmh-som exited with $som_status"; exit 1; }
echo "PASS"
