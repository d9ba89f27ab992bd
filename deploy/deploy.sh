#!/usr/bin/env bash
# Starts, stops or lists a deployment: which services run on which host, with which LCM URL and
# channel prefix, as a manifest (deploy/hosts/*.yaml) says. Each host runs the per-service launch
# scripts (deploy/launch/*.sh) in its checkout: locally when its ssh target is `local`, else over
# ssh (key login, BatchMode).
#
#   deploy/deploy.sh MANIFEST start|stop|status [--host NAME] [--netns DIR] [--dry-run]
#
#   --host NAME   only this host of the manifest
#   --netns DIR   run every host on this machine, host H inside the network namespace DIR/H
#                 (/run/netns for `ip netns add H`; tests link DIR/H to /proc/PID/ns/net)
#   --dry-run     print what each host would run, run nothing
# start goes in phases over all hosts (logger, planners, sim, goal); stop the other way round;
# status exits with 3 if any service is stopped. Exit code 1 if a host failed, 2 on a bad manifest.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
usage() { sed -n 7,14p "$0" | sed 's/^# \{0,1\}//' >&2; exit 2; }
[ $# -ge 2 ] || usage
manifest=$1
action=$2
shift 2
host_args=()
netns_dir=""
dry_run=0
while [ $# -gt 0 ]; do
  case "$1" in
    --host) host_args=(--host "${2:?--host needs a name}"); shift 2 ;;
    --netns) netns_dir=${2:?--netns needs a directory}; shift 2 ;;
    --dry-run) dry_run=1; shift ;;
    -h|--help) usage ;;
    *) echo "deploy.sh: unknown option $1" >&2; usage ;;
  esac
done
case "$action" in start|stop|status) ;; *) echo "deploy.sh: unknown action $action" >&2; usage ;; esac

plan=$(python3 "$here/manifest.py" "$manifest" "$action" "${host_args[@]}") || exit 2

is_local() {
  case "$1" in
    local|localhost|127.0.0.1|"$(hostname)"|"$(hostname -f 2>/dev/null || hostname)") return 0 ;;
  esac
  return 1
}

status=0
while IFS=$'\t' read -r host target command; do
  if [ -n "$netns_dir" ]; then
    runner=(nsenter "--net=$netns_dir/$host" -- sh -c "$command")
    where="netns $netns_dir/$host"
  elif is_local "$target"; then
    runner=(sh -c "$command")
    where=local
  else
    runner=(ssh -o BatchMode=yes -o ConnectTimeout=10 "$target" "$command")
    where="ssh $target"
  fi
  if [ $dry_run = 1 ]; then
    printf '%s (%s): %s\n' "$host" "$where" "$command"
    continue
  fi
  set +e
  "${runner[@]}" < /dev/null 2>&1 | sed "s/^/[$host] /"
  rc=${PIPESTATUS[0]}
  set -e
  if [ "$rc" -ne 0 ]; then
    if [ "$action" = status ] && [ "$rc" -eq 3 ]; then
      [ $status -eq 0 ] && status=3
    else
      echo "deploy.sh: host $host ($where) failed to $action (exit code $rc)" >&2
      status=1
    fi
  fi
done <<< "$plan"
exit $status
