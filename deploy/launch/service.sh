#!/usr/bin/env bash
# Start, stop or supervise one MMH service as a background process with a log file and a pid
# file. The per-service scripts (mapping.sh, som.sh, ...) call this with the executable's name.
# NAME mmh-logger is lcm-logger (deploy/record.sh) recording the prefix's channels (every channel
# without a prefix) to $MMH_RECORD_FILE (default RUN_DIR/<prefix>flight.lcm, then .00, .01, ...).
#
#   service.sh NAME start|stop|restart|status|run [options] [-- extra service arguments]
#
# options (each also from the environment):
#   --config FILE     MMH_CONFIG         configuration (default: deploy/config/default.yaml)
#                                        (installed from the package: /etc/mmh/mmh.yaml)
#   --lcm-url URL     LCM_DEFAULT_URL    LCM URL (default: LCM's udpm://239.255.76.67:7667?ttl=0)
#   --prefix P        MMH_PREFIX         channel prefix, e.g. UAV1_
#   --run-dir DIR     MMH_RUN_DIR        where NAME.log and NAME.pid go (default: $root/run;
#                                        package: /var/lib/mmh)
#   --bin-dir DIR     MMH_BIN_DIR        where the executables are (default: $root/build/bin;
#                                        package: /usr/bin)
#   --respawn         MMH_RESPAWN=1      restart the service whenever it exits (until stopped)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
# In a checkout: its build and configuration. Installed from the Debian package
# (/usr/lib/mmh-planner/launch), layout.sh next to this script names the package's paths.
root=$(cd "$here/../.." && pwd)
mmh_bin_dir=$root/build/bin
mmh_config=$root/deploy/config/default.yaml
mmh_run_dir=$root/run
mmh_record=$root/deploy/record.sh
if [ -f "$here/layout.sh" ]; then
  # shellcheck source=../package/layout.sh
  . "$here/layout.sh"
fi
name=${1:?usage: service.sh NAME start|stop|restart|status|run [options]}
action=${2:?usage: service.sh NAME start|stop|restart|status|run [options]}
shift 2

config=${MMH_CONFIG:-$mmh_config}
url=${LCM_DEFAULT_URL:-}
prefix=${MMH_PREFIX:-}
run_dir=${MMH_RUN_DIR:-$mmh_run_dir}
bin_dir=${MMH_BIN_DIR:-$mmh_bin_dir}
respawn=${MMH_RESPAWN:-0}
extra=()
while [ $# -gt 0 ]; do
  case "$1" in
    --config) config=$2; shift 2 ;;
    --lcm-url) url=$2; shift 2 ;;
    --prefix) prefix=$2; shift 2 ;;
    --run-dir) run_dir=$2; shift 2 ;;
    --bin-dir) bin_dir=$2; shift 2 ;;
    --respawn) respawn=1; shift ;;
    --) shift; extra=("$@"); break ;;
    *) echo "service.sh: unknown option $1" >&2; exit 2 ;;
  esac
done

exe=$bin_dir/$name
tag=${prefix}${name}
pid_file=$run_dir/$tag.pid
log_file=$run_dir/$tag.log
stop_file=$run_dir/$tag.stopping
if [ "$name" = mmh-logger ]; then
  exe=$mmh_record
  args=("${MMH_RECORD_FILE:-$run_dir/${prefix}flight.lcm}" --quiet)
  [ -n "$prefix" ] && args+=(--channel "^${prefix}.*")
else
  args=(--config "$config" --prefix "$prefix")
fi
[ -n "$url" ] && args+=(--lcm-url "$url")
args+=("${extra[@]}")

running_pid() {
  [ -f "$pid_file" ] || return 1
  local pid
  pid=$(cat "$pid_file")
  kill -0 "$pid" 2>/dev/null && echo "$pid"
}

case "$action" in
  run)
    exec "$exe" "${args[@]}"
    ;;
  start)
    if pid=$(running_pid); then echo "$tag already running (pid $pid)"; exit 0; fi
    [ -x "$exe" ] || { echo "$tag: $exe not found; build first (deploy/setup.sh) or install the package" >&2; exit 1; }
    mkdir -p "$run_dir"
    rm -f "$stop_file"
    if [ "$respawn" = 1 ]; then
      # A small supervisor restarts the service when it exits, until 'stop' is asked for.
      setsid bash -c '
        exe=$1; stop_file=$2; shift 2
        child=0
        trap "[ \$child -gt 0 ] && kill -TERM \$child 2>/dev/null; exit 0" TERM INT
        while [ ! -f "$stop_file" ]; do
          "$exe" "$@" & child=$!
          wait $child || true
          [ -f "$stop_file" ] && break
          echo "$(date +%T) supervisor: $exe exited, restarting in 1 s" >&2
          sleep 1
        done' supervisor "$exe" "$stop_file" "${args[@]}" >>"$log_file" 2>&1 < /dev/null &
    else
      setsid "$exe" "${args[@]}" >>"$log_file" 2>&1 < /dev/null &
    fi
    echo $! > "$pid_file"
    sleep 0.3
    if pid=$(running_pid); then
      echo "$tag started (pid $pid, log $log_file)"
    else
      echo "$tag failed to start; last lines of $log_file:" >&2
      tail -5 "$log_file" >&2
      rm -f "$pid_file"
      exit 1
    fi
    ;;
  stop)
    if ! pid=$(running_pid); then echo "$tag not running"; rm -f "$pid_file"; exit 0; fi
    touch "$stop_file"
    kill -TERM "$pid" 2>/dev/null || true
    for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    if kill -0 "$pid" 2>/dev/null; then
      echo "$tag did not stop in 5 s; killing" >&2
      kill -KILL -- "-$pid" 2>/dev/null || kill -KILL "$pid" 2>/dev/null || true
    fi
    # The supervisor's child is in the same session; make sure it is gone too.
    pkill -TERM -s "$pid" 2>/dev/null || true
    rm -f "$pid_file" "$stop_file"
    echo "$tag stopped"
    ;;
  restart)
    export MMH_CONFIG=$config MMH_PREFIX=$prefix MMH_RUN_DIR=$run_dir MMH_BIN_DIR=$bin_dir \
      MMH_RESPAWN=$respawn
    [ -n "$url" ] && export LCM_DEFAULT_URL=$url
    "$0" "$name" stop >/dev/null
    exec "$0" "$name" start -- "${extra[@]}"
    ;;
  status)
    if pid=$(running_pid); then echo "$tag running (pid $pid)"; else echo "$tag stopped"; exit 3; fi
    ;;
  *)
    echo "service.sh: unknown action $action (start|stop|restart|status|run)" >&2; exit 2 ;;
esac
