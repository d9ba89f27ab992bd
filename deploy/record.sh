#!/usr/bin/env bash
# Records every LCM channel (or a selection) to a log file with lcm-logger.
#
#   deploy/record.sh [FILE] [--lcm-url URL] [--channel REGEX] [--quiet]
#
# FILE defaults to logs/mmh-<date>.lcm; lcm-logger's -i always appends .00, .01, ... (the first
# free one), so an existing log is never overwritten and the log is FILE.00 the first time
# (Debian's --increment spelling is broken in LCM 1.3.1, -i works). The real name is printed.
# Stop with Ctrl-C (or SIGTERM); replay with lcm-logplayer FILE.00 (see docs/operations.md#record-and-replay).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
file=""
args=()
while [ $# -gt 0 ]; do
  case "$1" in
    --lcm-url) args+=("--lcm-url=$2"); shift 2 ;;
    --channel) args+=("--channel=$2"); shift 2 ;;
    --quiet) args+=("--quiet"); shift ;;
    -h|--help) sed -n 2,10p "$0"; exit 0 ;;
    *) file=$1; shift ;;
  esac
done
if [ -z "$file" ]; then
  mkdir -p "$root/logs"
  file=$root/logs/mmh-$(date +%Y%m%d-%H%M%S).lcm
fi
mkdir -p "$(dirname "$file")"
if [ -n "${LCM_DEFAULT_URL:-}" ] && ! printf '%s\n' "${args[@]:-}" | grep -q -- --lcm-url; then
  args+=("--lcm-url=$LCM_DEFAULT_URL")
fi
n=0
while [ -e "$(printf '%s.%02d' "$file" "$n")" ]; do n=$((n + 1)); done
echo "recording to $(printf '%s.%02d' "$file" "$n") (Ctrl-C to stop)" >&2
exec lcm-logger -i "${args[@]}" "$file"
