#!/usr/bin/env bash
# A short name for the Ansible playbooks of deploy/ansible/ (the deployment: the Debian package,
# systemd units, an inventory of hosts; see docs/operations.md#deployment).
#
#   deploy/deploy.sh [-i INVENTORY] deploy|start|stop|status [ansible-playbook options]
#   deploy/deploy.sh [-i INVENTORY] restart SERVICE [ansible-playbook options]
#
#   -i INVENTORY   default: deploy/ansible/inventory/three-hosts.yml
#   deploy         site.yml: install the package, write /etc/mmh/*.env, enable and start
#   restart NAME   restart.yml: rolling restart of one service, one host at a time
# Other options go to ansible-playbook (e.g. --limit planner, --check --diff).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
usage() { sed -n 5,11p "$0" | sed 's/^# \{0,1\}//' >&2; exit 2; }
inventory=$here/ansible/inventory/three-hosts.yml
if [ "${1:-}" = -i ]; then
  inventory=$(cd "$(dirname "${2:?-i needs an inventory}")" && pwd)/$(basename "$2")
  shift 2
fi
[ $# -ge 1 ] || usage
action=$1
shift
extra=()
case "$action" in
  deploy) playbook=site.yml ;;
  start|stop|status) playbook=$action.yml ;;
  restart) [ $# -ge 1 ] || usage; playbook=restart.yml; extra=(-e "mmh_service=$1"); shift ;;
  -h|--help) usage ;;
  *) echo "deploy.sh: unknown action $action" >&2; usage ;;
esac
command -v ansible-playbook > /dev/null ||
  { echo "deploy.sh: ansible-playbook missing (sudo apt-get install ansible, or deploy/setup.sh)" >&2; exit 1; }
export ANSIBLE_CONFIG=${ANSIBLE_CONFIG:-$here/ansible/ansible.cfg}
exec ansible-playbook -i "$inventory" "${extra[@]}" "$@" "$here/ansible/$playbook"
