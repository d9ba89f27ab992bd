#!/usr/bin/env bash
# Runs a command inside a private network namespace with only a loopback interface and a
# multicast route on it (docs/operations.md, "Several machines"): udpm:// traffic cannot leave this machine.
# Usage: netns.sh COMMAND [ARGS...]   (needs no root: unshare -r maps the user to root)
# LCM's URL there (unless LCM_DEFAULT_URL is set) asks for 2 MB receive buffers, as
# docs/operations.md asks of a vehicle (the kernel's net.core.rmem_max caps it): a busy test
# machine otherwise drops whole messages, scans and commits alike.
set -euo pipefail
if [ "${MMH_IN_NETNS:-0}" = 1 ]; then exec "$@"; fi
export LCM_DEFAULT_URL=${LCM_DEFAULT_URL:-'udpm://239.255.76.67:7667?ttl=0&recv_buf_size=2097152'}
exec unshare -rn bash -c '
  set -e
  ip link set lo up
  ip route add 224.0.0.0/4 dev lo
  export MMH_IN_NETNS=1
  exec "$@"' netns "$@"
