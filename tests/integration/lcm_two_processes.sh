#!/usr/bin/env bash
# Two real processes exchange messages over udpm:// inside a private network namespace.
set -euo pipefail
build=$1
here=$(cd "$(dirname "$0")" && pwd)
if [ "${MMH_IN_NETNS:-0}" != 1 ]; then exec "$here/netns.sh" bash "$0" "$@"; fi

url="udpm://239.255.76.67:7667?ttl=0"
check=$build/bin/mmh-lcm-check
"$check" --lcm-url "$url" --receive --count 5 --timeout 20 --prefix T1_ > /tmp/mmh_rx.$$ 2>&1 &
rx=$!
sleep 0.3
"$check" --lcm-url "$url" --send --count 20 --period 0.05 --prefix T1_
status=0
wait $rx || status=$?
cat /tmp/mmh_rx.$$
rm -f /tmp/mmh_rx.$$
[ $status -eq 0 ] || { echo "FAIL: receiver did not get the messages"; exit 1; }

# Without a multicast route a node must refuse to start with a clear hint.
out=$(unshare -rn "$check" --lcm-url "$url" --receive --count 1 --timeout 1 2>&1 || true)
echo "$out" | grep -q "multicast route" || { echo "FAIL: no clear error without a route: $out"; exit 1; }
echo "PASS"
