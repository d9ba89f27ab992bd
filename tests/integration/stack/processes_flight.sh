#!/usr/bin/env bash
# The same mission with every service as a separate process over udpm:// (LCM's default URL,
# ttl=0) inside a private network namespace, launched with the project's launch scripts, in real
# time: the vehicle reaches the goal without collision, and the launch scripts stop everything.
set -euo pipefail
build=$1
root=$(cd "$(dirname "$0")/../../.." && pwd)
if [ "${MMH_IN_NETNS:-0}" != 1 ]; then exec "$root/tests/integration/netns.sh" bash "$0" "$@"; fi
run=$(mktemp -d)
export MMH_BIN_DIR=$build/bin
cleanup() { "$root/deploy/launch/stack.sh" stop --run-dir "$run" >/dev/null 2>&1 || true; }
trap 'cleanup; rm -rf "$run"' EXIT
"$root/deploy/launch/stack.sh" start --run-dir "$run" \
  --sim-args "--world forest --density 0.1 --seed 7 --realtime" --goal 19.95,0,1.2
"$root/deploy/launch/stack.sh" status --run-dir "$run"
status=0
"$build/bin/mmh-mission-report" --timeout 90 || status=$?
if [ $status -ne 0 ]; then
  echo "FAIL: mission not completed (status $status)"
  for f in "$run"/*.log; do echo "== $f"; tail -5 "$f"; done
  exit 1
fi
cleanup
# Every service stopped and its pid file is gone.
if "$root/deploy/launch/stack.sh" status --run-dir "$run" | grep -q running; then
  echo "FAIL: services still running after stop"; exit 1
fi
ls "$run"/*.pid >/dev/null 2>&1 && { echo "FAIL: pid files left"; exit 1; }
echo PASS
