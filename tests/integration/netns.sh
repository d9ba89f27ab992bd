#!/usr/bin/env bash
# Runs a command inside a private network namespace with only a loopback interface and a
# multicast route on it (docs/operations.md, "Several machines"): udpm:// traffic cannot leave this machine.
# Usage: netns.sh COMMAND [ARGS...]   (needs no root: unshare -r maps the user to root)
set -euo pipefail
if [ "${MMH_IN_NETNS:-0}" = 1 ]; then exec "$@"; fi
exec unshare -rn bash -c '
  set -e
  ip link set lo up
  ip route add 224.0.0.0/4 dev lo
  export MMH_IN_NETNS=1
  exec "$@"' netns "$@"
