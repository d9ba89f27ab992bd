#!/usr/bin/env bash
# Start, stop or list the whole planner stack on this machine, each service as its own process.
#
#   stack.sh start|stop|status [service.sh options] [--with-sim] [--sim-args "ARGS"] [--goal x,y,z]
#            [--with-setpoint]
#
# Services: mmh-mapping, mmh-awareness, mmh-fpm, mmh-som, mmh-eam, mmh-arbiter; with --with-sim
# also mmh-sim (started last, so that everyone already listens) and, with --goal, a GOAL
# publisher (mmh-goal); with --with-setpoint also mmh-setpoint, the trajectory server (started
# with the planners; give the simulator --follow setpoint to fly its SETPOINT). Options such as --config, --lcm-url, --prefix, --run-dir and --respawn
# are passed to every service (see service.sh).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
action=${1:?usage: stack.sh start|stop|status [options]}
shift
common=()
with_sim=0
with_setpoint=0
sim_args=""
goal=""
while [ $# -gt 0 ]; do
  case "$1" in
    --with-sim) with_sim=1; shift ;;
    --with-setpoint) with_setpoint=1; shift ;;
    --sim-args) sim_args=$2; with_sim=1; shift 2 ;;
    --goal) goal=$2; shift 2 ;;
    --respawn) common+=("$1"); shift ;;
    *) common+=("$1" "$2"); shift 2 ;;
  esac
done
planners=(mmh-mapping mmh-awareness mmh-fpm mmh-som mmh-eam mmh-arbiter)
[ $with_setpoint = 1 ] && planners+=(mmh-setpoint)

case "$action" in
  start)
    for s in "${planners[@]}"; do "$here/service.sh" "$s" start "${common[@]}"; done
    if [ $with_sim = 1 ]; then
      # shellcheck disable=SC2086
      "$here/service.sh" mmh-sim start "${common[@]}" -- $sim_args
    fi
    if [ -n "$goal" ]; then "$here/service.sh" mmh-goal start "${common[@]}" -- --goal "$goal"; fi
    ;;
  stop)
    "$here/service.sh" mmh-goal stop "${common[@]}" || true
    "$here/service.sh" mmh-sim stop "${common[@]}" || true
    for s in "${planners[@]}"; do "$here/service.sh" "$s" stop "${common[@]}" || true; done
    # Also one started with --with-setpoint, whatever this call says.
    [ $with_setpoint = 1 ] || "$here/service.sh" mmh-setpoint stop "${common[@]}" >/dev/null 2>&1 || true
    ;;
  status)
    status=0
    for s in "${planners[@]}" mmh-sim mmh-goal; do "$here/service.sh" "$s" status "${common[@]}" || status=3; done
    exit $status
    ;;
  *) echo "stack.sh: unknown action $action (start|stop|status)" >&2; exit 2 ;;
esac
