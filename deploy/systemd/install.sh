#!/usr/bin/env bash
# Installs the mmh@.service template for this checkout and enables (and starts) the given
# services at boot, e.g. on the flight computer: deploy/systemd/install.sh --user mmh mapping sim
#
#   deploy/systemd/install.sh [--user USER] [--dest DIR] [--no-enable] SERVICE...
#
#   --user USER   the account the services run as (default: the caller, or $SUDO_USER)
#   --dest DIR    install under DIR instead of / (for packaging and tests; implies --no-enable)
#   --no-enable   only write the files
# Writes DIR/etc/systemd/system/mmh@.service and, if missing, DIR/etc/mmh/mmh.env (shared
# settings: LCM URL, prefix, config); MMH_ARGS for one service go into DIR/etc/mmh/SERVICE.env.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
user=${SUDO_USER:-$(id -un)}
dest=""
enable=1
services=()
while [ $# -gt 0 ]; do
  case "$1" in
    --user) user=$2; shift 2 ;;
    --dest) dest=$2; enable=0; shift 2 ;;
    --no-enable) enable=0; shift ;;
    -h|--help) sed -n 2,12p "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    -*) echo "install.sh: unknown option $1" >&2; exit 2 ;;
    *) services+=("$1"); shift ;;
  esac
done
for s in "${services[@]}"; do
  [ -x "$root/deploy/launch/$s.sh" ] || { echo "install.sh: no deploy/launch/$s.sh" >&2; exit 2; }
done
mkdir -p "$dest/etc/systemd/system" "$dest/etc/mmh"
sed -e "s|@ROOT@|$root|g" -e "s|@USER@|$user|g" "$root/deploy/systemd/mmh@.service" \
  > "$dest/etc/systemd/system/mmh@.service"
[ -f "$dest/etc/mmh/mmh.env" ] || cp "$root/deploy/systemd/mmh.env" "$dest/etc/mmh/mmh.env"
echo "installed $dest/etc/systemd/system/mmh@.service (root $root, user $user)"
if [ $enable = 1 ] && [ ${#services[@]} -gt 0 ]; then
  systemctl daemon-reload
  for s in "${services[@]}"; do systemctl enable --now "mmh@$s.service"; done
fi
