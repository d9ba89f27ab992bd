#!/usr/bin/env bash
# deploy/deploy.sh without starting anything: the example manifests parse, --dry-run shows each
# host's commands (ssh targets, phases: logger, planners, sim, goal; stop in reverse), --host
# selects one host, bad manifests are refused with exit code 2 and the reason; the systemd
# template installs for this checkout and passes systemd-analyze verify, and what it runs is the
# service itself in the foreground, stopping cleanly on SIGTERM.
set -euo pipefail
build=$1
root=$(cd "$(dirname "$0")/../../.." && pwd)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
deploy=$root/deploy/deploy.sh
fail() { echo "FAIL: $*"; exit 1; }

"$deploy" "$root/deploy/hosts/three-hosts.yaml" start --dry-run > "$out/start.txt"
cat "$out/start.txt"
[ "$(sed 's/: .*/:/' "$out/start.txt" | tr '\n' '|')" = \
  "ground (local):|vehicle (ssh mmh@192.168.10.2):|planner (ssh mmh@192.168.10.3):|vehicle (ssh mmh@192.168.10.2):|ground (local):|" ] ||
  fail "start phases or ssh targets wrong"
grep -q "logger.sh start --prefix UAV1_ .*--lcm-url 'udpm://239.255.76.67:7667?ttl=1'" "$out/start.txt" ||
  fail "logger without prefix or ttl=1 URL"
sed -n 3p "$out/start.txt" | grep -q "awareness.sh start.*fpm.sh start.*som.sh start.*eam.sh start.*arbiter.sh start.*--respawn" ||
  fail "planner host line wrong"
sed -n 4p "$out/start.txt" | grep -q "sim.sh start .* -- --world forest" || fail "sim arguments lost"
"$deploy" "$root/deploy/hosts/three-hosts.yaml" stop --dry-run > "$out/stop.txt"
[ "$(cut -d' ' -f1 "$out/stop.txt" | tr '\n' ' ')" = "ground vehicle vehicle planner ground " ] ||
  fail "stop order wrong: $(cut -d' ' -f1 "$out/stop.txt" | tr '\n' ' ')"
sed -n 4p "$out/stop.txt" | grep -q "arbiter.sh stop.*awareness.sh stop" || fail "planners not stopped in reverse"
"$deploy" "$root/deploy/hosts/three-hosts.yaml" status --dry-run --host planner > "$out/one.txt"
[ "$(wc -l < "$out/one.txt")" -eq 1 ] && grep -q "^planner (ssh" "$out/one.txt" || fail "--host planner"
"$deploy" "$root/deploy/hosts/single.yaml" start --dry-run > "$out/single.txt"
grep -q "^local (local): cd $root" "$out/single.txt" ||
  fail "single.yaml does not run locally in this checkout"
# --netns: every host on this machine inside DIR/HOST.
"$deploy" "$root/deploy/hosts/three-hosts.yaml" status --dry-run --netns /run/netns > "$out/ns.txt"
grep -q "^vehicle (netns /run/netns/vehicle)" "$out/ns.txt" || fail "--netns not applied"

expect_error() {  # expect_error MESSAGE-REGEX deploy.sh-args...
  local pattern=$1 status=0
  shift
  "$deploy" "$@" > "$out/err.txt" 2>&1 || status=$?
  [ $status -eq 2 ] || fail "'deploy.sh $*' exit code $status, not 2"
  grep -qE "$pattern" "$out/err.txt" || { cat "$out/err.txt"; fail "no '$pattern' for 'deploy.sh $*'"; }
}
printf 'hosts:\n  a:\n    services: [mapping, planner9]\n' > "$out/bad_service.yaml"
printf 'hosts:\n  a:\n    sevices: [mapping]\n' > "$out/bad_key.yaml"
printf 'hosts: [\n' > "$out/bad_yaml.yaml"
printf 'prefix: X_\n' > "$out/no_hosts.yaml"
expect_error "unknown service 'planner9'" "$out/bad_service.yaml" status
expect_error "unknown key.*sevices" "$out/bad_key.yaml" status
expect_error "not valid YAML" "$out/bad_yaml.yaml" status
expect_error "needs a 'hosts' mapping" "$out/no_hosts.yaml" status
expect_error "cannot read" "$out/missing.yaml" status
expect_error "no host nowhere" "$root/deploy/hosts/single.yaml" status --host nowhere
expect_error "unknown action" "$root/deploy/hosts/single.yaml" restart

# systemd: the template, installed under a scratch root, names this checkout and verifies.
"$root/deploy/systemd/install.sh" --dest "$out/sys" --user root mapping sim > /dev/null
unit=$out/sys/etc/systemd/system/mmh@.service
grep -q "ExecStart=$root/deploy/launch/%i.sh run -- \$MMH_ARGS" "$unit" || fail "ExecStart"
grep -q "@ROOT@\|@USER@" "$unit" && fail "placeholders left in $unit"
[ -f "$out/sys/etc/mmh/mmh.env" ] || fail "no mmh.env installed"
if command -v systemd-analyze > /dev/null; then
  cp "$unit" "$out/sys/mmh@mapping.service"
  systemd-analyze verify --man=no "$out/sys/mmh@mapping.service" 2> "$out/verify.txt" || true
  cat "$out/verify.txt"
  # Problems in the unit are reported as FILE:LINE (others are about this machine).
  grep -q "mmh@mapping.service:[0-9]" "$out/verify.txt" && fail "systemd-analyze verify: the unit"
fi
# What the unit runs (`%i.sh run`): the service itself in the foreground (same pid, so systemd
# supervises it), stopping cleanly on SIGTERM (memq:// here: no network needed).
LCM_DEFAULT_URL=memq:// MMH_BIN_DIR=$build/bin "$root/deploy/launch/mapping.sh" run \
  > "$out/run.log" 2>&1 &
pid=$!
sleep 1
[ "$(readlink "/proc/$pid/exe")" = "$(readlink -f "$build/bin/mmh-mapping")" ] ||
  fail "'mapping.sh run' is not the service itself: $(readlink "/proc/$pid/exe")"
kill -TERM $pid
status=0
wait $pid || status=$?
[ $status -eq 0 ] || { cat "$out/run.log"; fail "'mapping.sh run' exit code $status on SIGTERM"; }
echo PASS
