#!/usr/bin/env bash
# Three hosts deployed the way the docs say (docs/operations.md#deployment): the Debian package
# (cpack), Ansible over ssh, the example inventory deploy/ansible/inventory/three-hosts.yml.
# Everything runs in namespaces this test makes, so no packet leaves them and nothing is written
# to the machine's own /:
#   - the test's own network, mount and pid namespaces (the bridge "switch", the Ansible
#     controller at 10.213.0.1; every process dies with the test);
#   - per host (vehicle, planner, ground): network, UTS, mount and pid namespaces, a root that is
#     an overlay of / with a tmpfs on top (dpkg installs there), an sshd on 10.213.0.N with a key
#     made for the test. Without systemd in there, the inventory says mmh_supervisor: script.
# Checks: the play installs, configures and starts everything (ttl=1 across the bridge); the
# installed services read /etc/mmh/mmh.yaml; status.yml sees every unit and HEARTBEAT; a rolling
# restart of SOM during a mission there and back keeps the vehicle safe (both waypoints reached
# without collision, trajectories committed after the restart); a second run of the play changes
# nothing; the ground station's log holds every channel on the network (a reference recorder on
# the planner host) and the core ones; stop.yml stops everything and status.yml then fails.
set -euo pipefail
build=$1
root=$(cd "$(dirname "$0")/../../.." && pwd)
if [ "${MMH_DEPLOY_NS:-0}" != 1 ]; then
  if [ "$(id -u)" -ne 0 ]; then
    echo "SKIP: needs root (namespaces, overlay mounts and sshd as root inside them)"; exit 77
  fi
  for tool in ansible-playbook /usr/sbin/sshd ssh-keygen cpack unshare nsenter; do
    command -v "$tool" > /dev/null || { echo "FAIL: $tool missing: run deploy/setup.sh"; exit 1; }
  done
  # The pid namespace's first process is this script: when it exits, the kernel kills the rest.
  MMH_DEPLOY_NS=1 exec unshare --net --mount --pid --fork --kill-child --mount-proc \
    --propagation private bash "$0" "$@"
fi
started=$(date +%s)
out=$(mktemp -d /tmp/mmh-three-hosts.XXXXXX)
mount -t tmpfs -o size=4g,mode=0755 mmh-hosts "$out"  # private to this mount namespace
cleanup() {
  set +e
  # unshare ignores SIGTERM while it waits; SIGKILL takes its host's pid namespace with it.
  for pid in "${host_pids[@]:-}"; do [ -n "$pid" ] && kill -KILL "$pid" 2>/dev/null; done
  [ -n "${reference:-}" ] && kill "$reference" 2>/dev/null
  for pid in "${host_pids[@]:-}" ${reference:-}; do wait "$pid" 2>/dev/null; done
  umount -l "$out" 2>/dev/null
  rmdir "$out" 2>/dev/null
}
trap cleanup EXIT
fail() {
  echo "FAIL: $*"
  for f in "$out"/hosts/*/upper/var/lib/mmh/*.log; do [ -f "$f" ] && { echo "== $f"; tail -5 "$f"; }; done
  exit 1
}
step() { echo "== $(( $(date +%s) - started )) s: $*"; }

step "the package"
cpack -G DEB -B "$out/pkg" --config "$build/CPackConfig.cmake" > "$out/cpack.log" 2>&1 ||
  { cat "$out/cpack.log"; fail "cpack -G DEB"; }
deb=$(ls "$out"/pkg/mmh-planner_*.deb)

step "the network: a bridge, three hosts, an sshd on each"
ip link set lo up
ip link add mmhbr0 type bridge
ip link set mmhbr0 type bridge mcast_snooping 0
ip link set mmhbr0 up
ip addr add 10.213.0.1/24 dev mmhbr0
ssh-keygen -q -t ed25519 -N '' -C mmh-test -f "$out/id_ed25519"
host_pids=()
hosts=(vehicle planner ground)
for i in 0 1 2; do
  host=${hosts[$i]} addr=10.213.0.$((i + 2)) dir=$out/hosts/${hosts[$i]}
  mkdir -p "$dir"
  # The host: its namespaces; once eth0 has arrived, its network and root, then its sshd.
  unshare --net --uts --mount --pid --fork --kill-child --propagation private bash -c '
    set -euo pipefail
    host=$1 addr=$2 dir=$3 key=$4
    hostname "$host"
    ip link set lo up
    for _ in $(seq 100); do ip link show eth0 > /dev/null 2>&1 && break; sleep 0.05; done
    ip link set eth0 up
    ip addr add "$addr/24" dev eth0
    ip route add 224.0.0.0/4 dev eth0
    mkdir -p "$dir/upper" "$dir/work" "$dir/merged"
    mount -t overlay overlay -o "lowerdir=/,upperdir=$dir/upper,workdir=$dir/work" "$dir/merged"
    m=$dir/merged
    mount -t proc proc "$m/proc"
    mount --rbind /dev "$m/dev"
    mount -t tmpfs tmpfs "$m/run"
    mount -t tmpfs tmpfs "$m/tmp"
    mkdir -p "$m/run/sshd"
    rm -f "$m"/etc/ssh/ssh_host_*
    ssh-keygen -q -t ed25519 -N "" -f "$m/etc/ssh/ssh_host_ed25519_key"
    cp "$key.pub" "$m/etc/ssh/mmh_test_authorized_keys"
    cat > "$m/etc/ssh/sshd_mmh_test.conf" <<CONF
ListenAddress $addr
HostKey /etc/ssh/ssh_host_ed25519_key
PermitRootLogin prohibit-password
AuthorizedKeysFile /etc/ssh/mmh_test_authorized_keys
PasswordAuthentication no
KbdInteractiveAuthentication no
UsePAM no
StrictModes no
PidFile /run/sshd.pid
Subsystem sftp internal-sftp
CONF
    # bash stays the namespace'\''s init (it reaps the services that the launch scripts detach).
    chroot "$m" /usr/sbin/sshd -D -e -f /etc/ssh/sshd_mmh_test.conf &
    wait' host "$host" "$addr" "$dir" "$out/id_ed25519" > "$dir/host.log" 2>&1 &
  host_pids+=($!)
  for _ in $(seq 100); do  # until unshare has made the host's network namespace
    [ "$(readlink "/proc/${host_pids[-1]}/ns/net")" != "$(readlink /proc/self/ns/net)" ] && break
    sleep 0.02
  done
  ip link add "mmh-$host" type veth peer name eth0 netns "${host_pids[-1]}"
  ip link set "mmh-$host" master mmhbr0 up
done
for i in 0 1 2; do
  host=${hosts[$i]} addr=10.213.0.$((i + 2))
  for _ in $(seq 100); do
    [ -f "$out/hosts/$host/upper/etc/ssh/ssh_host_ed25519_key.pub" ] &&
      (exec 3<> "/dev/tcp/$addr/22") 2>/dev/null && break
    sleep 0.1
  done
  echo "$addr $(cut -d' ' -f1,2 "$out/hosts/$host/upper/etc/ssh/ssh_host_ed25519_key.pub")" \
    >> "$out/known_hosts"
done
ssh_opts=(-o BatchMode=yes -o UserKnownHostsFile="$out/known_hosts" -o StrictHostKeyChecking=yes
  -i "$out/id_ed25519")
on() { local host=$1; shift; ssh "${ssh_opts[@]}" "root@$host" "$@"; }
on 10.213.0.4 hostname | grep -qx ground || fail "no ssh to the ground station"

# The example inventory with this test's addresses, key and supervisor on top (a later
# inventory source wins).
cat > "$out/test-hosts.yml" <<YAML
all:
  vars:
    ansible_ssh_private_key_file: $out/id_ed25519
    ansible_ssh_common_args: -o UserKnownHostsFile=$out/known_hosts -o StrictHostKeyChecking=yes
    mmh_package_file: $deb
    mmh_supervisor: script        # no systemd in the test's hosts
  hosts:
    vehicle: {ansible_host: 10.213.0.2}
    planner: {ansible_host: 10.213.0.3}
    # There and back: the way back is a goal change that the planner must answer, so that
    # trajectories come after SOM's restart however quickly the first leg is flown.
    ground: {ansible_host: 10.213.0.4, mmh_service_args: {goal: "--waypoints 19.95,0,1.2;-19.95,0,1.2"}}
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
nsenter --net="/proc/${host_pids[1]}/ns/net" lcm-logger -q \
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

step "ansible-playbook site.yml again: no change"
play again site.yml || { cat "$out/again.txt"; fail "site.yml (second run)"; }
recap again
[ "$(recap again | grep -c 'changed=0 .*failed=0')" -eq 3 ] ||
  { cat "$out/again.txt"; fail "the second run changed something"; }

step "ansible-playbook status.yml"
play status status.yml || { cat "$out/status.txt"; fail "status.yml"; }
grep -E 'mmh-(som|arbiter|mapping|sim) ' "$out/status.txt" | head -8

step "ansible-playbook stop.yml"
play stop stop.yml || { cat "$out/stop.txt"; fail "stop.yml"; }
recap stop
play stopped status.yml && fail "status.yml succeeds after stop"
grep -q "not running: \[.*som" "$out/stopped.txt" || { cat "$out/stopped.txt"; fail "status after stop"; }
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
