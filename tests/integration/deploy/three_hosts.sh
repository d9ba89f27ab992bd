#!/usr/bin/env bash
# Three hosts deployed the way the docs say (docs/operations.md#deployment): the Debian package
# (cpack), Ansible over ssh, the example inventory deploy/ansible/inventory/three-hosts.yml.
# Everything runs in namespaces this test makes, so no packet leaves them and nothing is written
# to the machine's own /:
#   - the test's own network, mount and pid namespaces (the bridge "switch", the Ansible
#     controller at 10.213.0.1; every process dies with the test);
#   - per host (vehicle, planner, ground): a network namespace on the bridge (10.213.0.N) and a
#     clean Debian 12 booted by systemd in systemd-nspawn, its root an overlay of the Debian 12
#     that the test integration_deploy_debian12 makes (debian12.sh: debootstrap, with the
#     package's dependencies), its sshd started by systemd with a key made for the test.
# The vehicle and the planner run the services as systemd units (mmh@NAME, the inventory's
# default); the ground station uses the launch scripts' supervisor (mmh_supervisor: script, for
# computers without systemd), so both ways are exercised.
# Checks: the play installs, configures, enables and starts everything (ttl=1 across the
# bridge); the units run as the system user mmh and read /etc/mmh/mmh.yaml; status.yml sees every
# unit and HEARTBEAT; a rolling restart of SOM during a mission there and back keeps the vehicle
# safe (both waypoints reached without collision, trajectories committed after the restart);
# systemd restarts a service that was killed; a second run of the play changes nothing; the
# ground station's log holds every channel on the network (a reference recorder on the planner
# host) and the core ones; stop.yml stops everything and status.yml then fails.
set -euo pipefail
build=$(cd "$1" && pwd)
root=$(cd "$(dirname "$0")/../../.." && pwd)
debian12=$build/deploy-test/debian12
debian12_deps=$build/deploy-test/debian12-deps
if [ "${MMH_DEPLOY_NS:-0}" != 1 ]; then
  if [ "$(id -u)" -ne 0 ]; then
    echo "SKIP: needs root (namespaces, overlay mounts, containers)"; exit 77
  fi
  for tool in ansible-playbook ssh-keygen cpack unshare nsenter systemd-nspawn; do
    command -v "$tool" > /dev/null || { echo "FAIL: $tool missing: run deploy/setup.sh"; exit 1; }
  done
  if [ ! -f "$debian12/.complete" ] || [ ! -d "$debian12_deps" ]; then
    echo "FAIL: no Debian 12 root in $build/deploy-test: the test integration_deploy_debian12 makes it"
    exit 1
  fi
  # The pid namespace's first process is this script: when it exits, the kernel kills the rest.
  MMH_DEPLOY_NS=1 exec unshare --net --mount --pid --fork --kill-child --mount-proc \
    --propagation private bash "$0" "$@"
fi
started=$(date +%s)
out=$(mktemp -d /tmp/mmh-three-hosts.XXXXXX)
mount -t tmpfs -o size=4g,mode=0755 mmh-hosts "$out"  # private to this mount namespace
cgroup_name=mmh-three-hosts-$$-$(basename "$out")
host_pids=()
all_cgroups=()
cleanup() {
  set +e
  [ -n "${reference:-}" ] && kill "$reference" 2> /dev/null
  # SIGTERM: systemd-nspawn asks the container's systemd to power off; SIGKILL if it lingers.
  for pid in "${host_pids[@]}"; do kill -TERM "$pid" 2> /dev/null; done
  for _ in $(seq 100); do
    alive=0
    for pid in "${host_pids[@]}"; do kill -0 "$pid" 2> /dev/null && alive=1; done
    [ $alive = 0 ] && break
    sleep 0.1
  done
  for pid in "${host_pids[@]}"; do kill -KILL "$pid" 2> /dev/null; done
  for pid in "${host_pids[@]}" ${reference:-}; do wait "$pid" 2> /dev/null; done
  for c in "${all_cgroups[@]}"; do find "$c" -depth -type d -exec rmdir {} + 2> /dev/null; done
  umount -R "$out" 2> /dev/null || umount -l "$out" 2> /dev/null
  rmdir "$out" 2> /dev/null
}
trap cleanup EXIT
fail() {
  echo "FAIL: $*"
  for i in 0 1 2; do
    echo "== ${hosts[$i]:-}: the mmh units' journal"
    timeout 10 ssh "${ssh_opts[@]}" "root@10.213.0.$((i + 2))" \
      "journalctl --no-pager -n 15 -u 'mmh@*'; tail -n 5 /var/lib/mmh/*.log" 2>&1 | tail -40 || true
  done
  exit 1
}
step() { echo "== $(( $(date +%s) - started )) s: $*"; }
ssh_opts=(-o BatchMode=yes -o UserKnownHostsFile="$out/known_hosts" -o StrictHostKeyChecking=yes
  -i "$out/id_ed25519")

step "the package"
cpack -G DEB -B "$out/pkg" --config "$build/CPackConfig.cmake" > "$out/cpack.log" 2>&1 ||
  { cat "$out/cpack.log"; fail "cpack -G DEB"; }
deb=$(ls "$out"/pkg/mmh-planner_*.deb)

step "the network: a bridge and three hosts, each a Debian 12 booted by systemd"
ip link set lo up
ip link add mmhbr0 type bridge
ip link set mmhbr0 type bridge mcast_snooping 0
ip link set mmhbr0 up
ip addr add 10.213.0.1/24 dev mmhbr0
ssh-keygen -q -t ed25519 -N '' -C mmh-test -f "$out/id_ed25519"
# A /run of this mount namespace's own: ip netns and systemd-nspawn keep their state there.
mount -t tmpfs -o mode=0755 mmh-run /run
mkdir -p /run/netns
hosts=(vehicle planner ground)
for i in 0 1 2; do
  host=${hosts[$i]} addr=10.213.0.$((i + 2)) dir=$out/hosts/${hosts[$i]}
  ip netns add "$host"
  ip link add "mmh-$host" type veth peer name eth0 netns "$host"
  ip link set "mmh-$host" master mmhbr0 up
  ip -n "$host" link set lo up
  ip -n "$host" link set eth0 up
  ip -n "$host" addr add "$addr/24" dev eth0
  ip -n "$host" route add 224.0.0.0/4 dev eth0
  # Its root: the clean Debian 12 with the package's dependencies, this host's changes on top.
  mkdir -p "$dir/upper" "$dir/work" "$dir/merged"
  mount -t overlay overlay -o "lowerdir=$debian12_deps:$debian12,upperdir=$dir/upper,workdir=$dir/work" \
    "$dir/merged"
  m=$dir/merged
  echo "$host" > "$m/etc/hostname"
  rm -f "$m"/etc/ssh/ssh_host_*
  ssh-keygen -q -A -f "$m" > /dev/null
  install -d -m 0700 "$m/root/.ssh"
  install -m 0600 "$out/id_ed25519.pub" "$m/root/.ssh/authorized_keys"
  printf 'PasswordAuthentication no\nKbdInteractiveAuthentication no\n' \
    > "$m/etc/ssh/sshd_config.d/mmh-test.conf"
  echo "$addr $(cut -d' ' -f1,2 "$m/etc/ssh/ssh_host_ed25519_key.pub")" >> "$out/known_hosts"
  # Each container in a cgroup of its own, where its systemd makes its slices.
  cgroups=()
  for hierarchy in /sys/fs/cgroup/unified /sys/fs/cgroup/systemd /sys/fs/cgroup; do
    if [ -w "$hierarchy/cgroup.procs" ]; then
      mkdir -p "$hierarchy/$cgroup_name-$host"
      cgroups+=("$hierarchy/$cgroup_name-$host")
    fi
  done
  all_cgroups+=("${cgroups[@]}")
  (
    for c in "${cgroups[@]}"; do echo "$BASHPID" > "$c/cgroup.procs"; done
    exec systemd-nspawn --quiet --directory="$m" --machine="$host" --boot --register=no \
      --keep-unit --network-namespace-path="/run/netns/$host" --console=passive
  ) > "$dir/boot.log" 2>&1 &
  host_pids+=($!)
done
for i in 0 1 2; do
  addr=10.213.0.$((i + 2))
  for _ in $(seq 300); do (exec 3<> "/dev/tcp/$addr/22") 2> /dev/null && break; sleep 0.1; done
done
on() { local host=$1; shift; ssh "${ssh_opts[@]}" "root@$host" "$@"; }
for i in 0 1 2; do
  for _ in $(seq 100); do  # sshd listens before systemd has finished the boot
    [ "$(on "10.213.0.$((i + 2))" systemctl is-system-running 2> /dev/null)" = running ] && break
    sleep 0.2
  done
  state=$(on "10.213.0.$((i + 2))" systemctl is-system-running 2>&1 || true)
  [ "$state" = running ] || { cat "$out/hosts/${hosts[$i]}/boot.log"; fail "${hosts[$i]}: systemd $state"; }
done
on 10.213.0.4 hostname | grep -qx ground || fail "no ssh to the ground station"
on 10.213.0.2 cat /etc/debian_version | grep -q '^12\.' || fail "the vehicle is not Debian 12"

# The example inventory with this test's addresses and key on top (a later inventory source
# wins).
cat > "$out/test-hosts.yml" <<YAML
all:
  vars:
    ansible_ssh_private_key_file: $out/id_ed25519
    ansible_ssh_common_args: -o UserKnownHostsFile=$out/known_hosts -o StrictHostKeyChecking=yes
    mmh_package_file: $deb
  hosts:
    vehicle: {ansible_host: 10.213.0.2}
    planner: {ansible_host: 10.213.0.3}
    # There and back: the way back is a goal change that the planner must answer, so that
    # trajectories come after SOM's restart however quickly the first leg is flown. The ground
    # station as a computer without systemd: the launch scripts supervise.
    ground:
      ansible_host: 10.213.0.4
      mmh_supervisor: script
      mmh_service_args: {goal: "--waypoints 19.95,0,1.2;-19.95,0,1.2"}
YAML
export ANSIBLE_CONFIG=$root/deploy/ansible/ansible.cfg ANSIBLE_HOME=$out/ansible \
  ANSIBLE_NOCOLOR=1 ANSIBLE_FORCE_COLOR=0
play() {  # play NAME PLAYBOOK [args]: ansible-playbook on the example + test inventories
  local name=$1; shift
  ansible-playbook -i "$root/deploy/ansible/inventory/three-hosts.yml" -i "$out/test-hosts.yml" \
    "$root/deploy/ansible/$@" > "$out/$name.txt" 2>&1
}
recap() { sed -n '/^PLAY RECAP/,$p' "$out/$1.txt"; }

# Everything with the vehicle's prefix on the planner host's network, as a reference.
nsenter --net=/run/netns/planner lcm-logger -q \
  --lcm-url 'udpm://239.255.76.67:7667?ttl=1' "$out/reference.lcm" &
reference=$!

step "ansible-playbook site.yml: install, configure, start"
play deploy site.yml || { cat "$out/deploy.txt"; fail "site.yml"; }
recap deploy
grep -q 'ttl=1' "$out/hosts/planner/upper/etc/mmh/mmh.env" || fail "mmh.env without ttl=1"
grep -qx 'MMH_PREFIX="UAV1_"' "$out/hosts/vehicle/upper/etc/mmh/mmh.env" || fail "mmh.env prefix"
grep -q -- '--realtime' "$out/hosts/vehicle/upper/etc/mmh/sim.env" || fail "sim.env arguments"
on 10.213.0.3 mmh-config-check | grep -q "/etc/mmh/mmh.yaml" ||
  fail "the installed mmh-config-check does not read /etc/mmh/mmh.yaml"
# systemd runs the units, enabled for the next boot, as the system user mmh.
for service in mapping sim; do
  [ "$(on 10.213.0.2 systemctl is-enabled "mmh@$service")" = enabled ] || fail "mmh@$service not enabled"
done
for service in awareness fpm som eam arbiter; do
  [ "$(on 10.213.0.3 systemctl is-active "mmh@$service")" = active ] || fail "mmh@$service not active"
  pid=$(on 10.213.0.3 systemctl show -p MainPID --value "mmh@$service")
  [ "$(on 10.213.0.3 ps -o user=,comm= -p "$pid")" = "mmh      mmh-$service" ] ||
    fail "mmh@$service: $(on 10.213.0.3 ps -o user=,comm= -p "$pid")"
done
on 10.213.0.4 systemctl list-units --all --no-legend 'mmh@*' | grep -q . &&
  fail "units on the ground station, whose supervisor is the launch scripts"
on 10.213.0.4 "mmh-mission-report --prefix UAV1_ --timeout 100" > "$out/report.txt" 2>&1 &
report=$!

step "ansible-playbook restart.yml -e mmh_service=som (rolling restart during the flight)"
# (A shorter HEARTBEAT listen than status.yml's, so that the restart falls well inside the
# flight: about 16 s there and 16 s back.)
play restart restart.yml -e mmh_service=som -e mmh_heartbeat_listen_s=1.5 || { cat "$out/restart.txt"; fail "restart.yml"; }
recap restart
restarted=$(date +%s)
kill -0 $report 2>/dev/null || { cat "$out/report.txt"; fail "the mission ended before SOM's restart"; }
step "the mission"
wait $report || { cat "$out/report.txt"; fail "the vehicle did not reach its goal safely"; }
cat "$out/report.txt"

step "systemd restarts a killed service (Restart=on-failure)"
old=$(on 10.213.0.3 systemctl show -p MainPID --value mmh@awareness)
on 10.213.0.3 kill -KILL "$old"
new=$old
for _ in $(seq 100); do
  new=$(on 10.213.0.3 systemctl show -p MainPID --value mmh@awareness)
  [ "$new" != "$old" ] && [ "$new" != 0 ] &&
    [ "$(on 10.213.0.3 systemctl is-active mmh@awareness)" = active ] && break
  sleep 0.1
done
[ "$new" != "$old" ] && [ "$new" != 0 ] || fail "mmh@awareness was not restarted after SIGKILL"
echo "mmh@awareness: pid $old killed, systemd started pid $new"

step "ansible-playbook site.yml again: no change"
play again site.yml || { cat "$out/again.txt"; fail "site.yml (second run)"; }
recap again
[ "$(recap again | grep -c 'changed=0 .*failed=0')" -eq 3 ] ||
  { cat "$out/again.txt"; fail "the second run changed something"; }

step "ansible-playbook status.yml"
play status status.yml || { cat "$out/status.txt"; fail "status.yml"; }
grep -E 'mmh-(som|arbiter|mapping|sim) ' "$out/status.txt" | head -8

step "ansible-playbook site.yml with services taken off the inventory"
cat > "$out/retire.yml" <<YAML
all:
  hosts:
    vehicle: {mmh_services: [mapping]}
    ground: {mmh_services: [logger]}
YAML
play retire site.yml -i "$out/retire.yml" || { cat "$out/retire.txt"; fail "site.yml (retire)"; }
recap retire
state=$(on 10.213.0.2 "systemctl is-enabled mmh@sim; systemctl is-active mmh@sim" || true)
[ "$state" = $'disabled\ninactive' ] || fail "mmh@sim, no longer in the inventory, is $state"
[ "$(on 10.213.0.2 systemctl is-active mmh@mapping)" = active ] || fail "mmh@mapping stopped"
on 10.213.0.4 "pgrep -f /usr/bin/[m]mh-goal" && fail "mmh-goal, no longer in the inventory, runs"
grep -q 'changed: \[vehicle\] => (item=sim)' "$out/retire.txt" ||
  { cat "$out/retire.txt"; fail "the play did not report mmh@sim stopped"; }

step "ansible-playbook stop.yml"
play stop stop.yml || { cat "$out/stop.txt"; fail "stop.yml"; }
recap stop
play stopped status.yml && fail "status.yml succeeds after stop"
grep -q "not running: \[.*som" "$out/stopped.txt" || { cat "$out/stopped.txt"; fail "status after stop"; }
state=$(on 10.213.0.3 systemctl is-active mmh@som || true)
[ "$state" = inactive ] || fail "mmh@som is $state after stop"
for i in 0 1 2; do
  n=$(on "10.213.0.$((i + 2))" "pgrep -c -f '/usr/bin/[m]mh-|[l]cm-logger' || true")
  [ "$n" = 0 ] || fail "$n services still running on ${hosts[$i]} after stop"
done
kill "$reference"; wait "$reference" 2>/dev/null || true
reference=""

step "the ground station's log"
log=$out/hosts/ground/upper/var/lib/mmh/UAV1_flight.lcm.00
[ -f "$log" ] || fail "no $log"
channels() { python3 "$root/tests/integration/deploy/log_channels.py" "$@" | awk '{ print $1 }'; }
python3 "$root/tests/integration/deploy/log_channels.py" "$log"
channels "$log" > "$out/ground.txt"
channels "$out/reference.lcm" | grep '^UAV1_' > "$out/reference.txt"
missing=$(comm -23 <(sort "$out/reference.txt") <(sort "$out/ground.txt"))
[ -z "$missing" ] || fail "on the network but not in the ground station's log: $missing"
for c in ODOMETRY POINTCLOUD GOAL LOCAL_MAP AWARENESS PLAN_RESULT TRAJECTORY ARBITER_STATUS \
  HEARTBEAT MISSION_STATUS; do
  grep -qx "UAV1_$c" "$out/ground.txt" || fail "UAV1_$c missing from the ground station's log"
done
grep -q "^UAV1_PLAN_REQUEST_" "$out/ground.txt" || fail "no PLAN_REQUEST in the ground station's log"
# After SOM's restart the arbiter kept committing trajectories.
after=$(python3 "$root/tests/integration/deploy/log_channels.py" --since "$restarted" "$log" |
  awk '$1 == "UAV1_TRAJECTORY" { print $2 }')
[ "${after:-0}" -gt 0 ] || fail "no TRAJECTORY committed after SOM's restart"
echo "trajectories committed after SOM's restart: $after"
step "done"
echo PASS
