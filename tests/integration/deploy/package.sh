#!/usr/bin/env bash
# The Debian package and the Ansible files, without starting a deployment: cpack -G DEB builds
# mmh-planner_*.deb with the executables in /usr/bin, the launch scripts, the type jar and the
# lcm-spy wrapper, mmh-viewer's page (which the installed mmh-viewer serves without being told
# where it is), /etc/mmh/mmh.yaml as a conffile and the mmh@.service template; its Depends
# name Debian 12's runtime libraries and resolve on a Debian 12 without anything installed (apt
# in simulation on an empty dpkg status); lintian reports no error; the unit passes
# systemd-analyze verify and what it runs is the service itself in the foreground, stopping
# cleanly on SIGTERM; the playbooks pass ansible-playbook --syntax-check; the inventories give
# each vehicle group its prefix and ttl=1; deploy/deploy.sh passes its arguments to
# ansible-playbook.
set -euo pipefail
build=$1
root=$(cd "$(dirname "$0")/../../.." && pwd)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
for tool in cpack dpkg-deb lintian ansible-playbook ansible-inventory; do
  command -v "$tool" > /dev/null || fail "$tool missing: run deploy/setup.sh"
done

cpack -G DEB -B "$out" --config "$build/CPackConfig.cmake" > "$out/cpack.log" 2>&1 ||
  { cat "$out/cpack.log"; fail "cpack -G DEB"; }
deb=$(ls "$out"/mmh-planner_*.deb)
echo "package: $(basename "$deb") ($(du -k "$deb" | cut -f1) kB)"
dpkg-deb -c "$deb" | awk '{ print $6 }' | sed 's|^\./|/|' > "$out/files.txt"
for f in /usr/bin/mmh-mapping /usr/bin/mmh-awareness /usr/bin/mmh-fpm /usr/bin/mmh-som \
  /usr/bin/mmh-eam /usr/bin/mmh-arbiter /usr/bin/mmh-setpoint /usr/bin/mmh-sim /usr/bin/mmh-goal /usr/bin/mmh-top \
  /usr/bin/mmh-mission-report /usr/bin/mmh-lcm-check /usr/bin/mmh-config-check \
  /usr/bin/mmh-lcm-spy /usr/share/java/mmh-lcmtypes.jar /usr/lib/mmh-planner/lcm-spy \
  /usr/lib/mmh-planner/record.sh /usr/lib/mmh-planner/launch/service.sh \
  /usr/lib/mmh-planner/launch/som.sh /usr/lib/mmh-planner/launch/setpoint.sh /usr/lib/mmh-planner/launch/logger.sh \
  /usr/lib/mmh-planner/launch/layout.sh /etc/mmh/mmh.yaml /lib/systemd/system/mmh@.service \
  /usr/share/doc/mmh-planner/copyright /usr/share/doc/mmh-planner/changelog.Debian.gz; do
  grep -qx "$f" "$out/files.txt" || fail "$f not in the package"
done
grep -q '/usr/bin/mmh-microbench' "$out/files.txt" && fail "development tools in the package"
if [ -f "$build/viewer-web/index.html" ]; then
  for f in /usr/bin/mmh-viewer /usr/share/mmh-planner/viewer-web/index.html \
    /usr/share/mmh-planner/viewer-web/viewer.js /usr/share/mmh-planner/viewer-web/viewer.css; do
    grep -qx "$f" "$out/files.txt" || fail "$f not in the package"
  done
fi
dpkg-deb -e "$deb" "$out/control"
[ "$(cat "$out/control/conffiles")" = /etc/mmh/mmh.yaml ] || fail "conffiles: $(cat "$out/control/conffiles")"
depends=$(dpkg-deb -f "$deb" Depends)
echo "Depends: $depends"
for d in liblcm1 liboctomap libpcl-common libnlopt-cxx0 libyaml-cpp liblcm-bin adduser; do
  grep -q "$d" <<< "$depends" || fail "Depends lacks $d"
done
# The same configuration as the source tree's.
dpkg-deb -x "$deb" "$out/root"
cmp -s "$out/root/etc/mmh/mmh.yaml" "$root/deploy/config/default.yaml" || fail "/etc/mmh/mmh.yaml"
# Every dependency exists in Debian 12: apt resolves the package on an empty system (simulation,
# from the package lists that deploy/setup.sh's apt-get update fetched).
: > "$out/empty-status"
if ls /var/lib/apt/lists/*Packages* > /dev/null 2>&1; then
  apt-get -s -o Dir::State::status="$out/empty-status" -o Debug::NoLocking=1 install "$deb" \
    > "$out/apt.txt" 2>&1 || { tail -20 "$out/apt.txt"; fail "the dependencies do not resolve"; }
  echo "on an empty Debian 12, apt installs $(grep -c '^Inst ' "$out/apt.txt") packages with it"
else
  echo "(no apt package lists: the clean-install resolution is not checked)"
fi
lintian --tag-display-limit 0 "$deb" > "$out/lintian.txt" 2>&1 || true
cat "$out/lintian.txt"
grep -q '^E: ' "$out/lintian.txt" && fail "lintian reports errors"

# The installed mmh-viewer serves the installed page (found next to its executable), not the
# "page not built" notice (memq://: no network; an ephemeral port on 127.0.0.1).
if [ -f "$build/viewer-web/index.html" ]; then
  LCM_DEFAULT_URL=memq:// "$out/root/usr/bin/mmh-viewer" --bind 127.0.0.1:0 \
    > "$out/viewer.log" 2>&1 &
  viewer_pid=$!
  url=""
  for _ in $(seq 50); do
    url=$(grep -o 'http://127.0.0.1:[0-9]*/' "$out/viewer.log" | head -1 || true)
    [ -n "$url" ] && break
    sleep 0.1
  done
  [ -n "$url" ] || { cat "$out/viewer.log"; fail "the installed mmh-viewer printed no URL"; }
  python3 - "$url" "$out/root/usr/share/mmh-planner/viewer-web/index.html" <<'PY' ||
import sys, urllib.request
page = urllib.request.urlopen(sys.argv[1], timeout=10).read()
assert page == open(sys.argv[2], "rb").read(), page[:200]
PY
    { kill $viewer_pid; fail "the installed mmh-viewer does not serve the installed page"; }
  kill -TERM $viewer_pid
  wait $viewer_pid || true
  echo "the installed mmh-viewer serves /usr/share/mmh-planner/viewer-web at $url"
fi

# systemd: the unit verifies (problems in the unit come as FILE:LINE).
if command -v systemd-analyze > /dev/null; then
  cp "$out/root/lib/systemd/system/mmh@.service" "$out/mmh@mapping.service"
  systemd-analyze verify --man=no "$out/mmh@mapping.service" 2> "$out/verify.txt" || true
  grep "mmh@mapping.service:[0-9]" "$out/verify.txt" && fail "systemd-analyze verify: the unit"
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

# Ansible: the playbooks parse; the inventories' groups give the prefixes, ttl=1 everywhere.
export ANSIBLE_CONFIG=$root/deploy/ansible/ansible.cfg ANSIBLE_HOME=$out/ansible
inv=$root/deploy/ansible/inventory
for p in site start stop status restart; do
  ansible-playbook -i "$inv/three-hosts.yml" --syntax-check "$root/deploy/ansible/$p.yml" \
    > "$out/syntax.txt" 2>&1 || { cat "$out/syntax.txt"; fail "$p.yml"; }
done
ansible-inventory -i "$inv/two-vehicles.yml" --list > "$out/two.json"
ansible-inventory -i "$inv/three-hosts.yml" --list > "$out/three.json"
python3 - "$out/two.json" "$out/three.json" <<'PY' || fail "inventories"
import json, sys
two, three = (json.load(open(p)) for p in sys.argv[1:])
hv = two["_meta"]["hostvars"]
assert two["uav1"]["hosts"] == ["uav1-computer"] and two["uav2"]["hosts"] == ["uav2-computer"]
assert hv["uav1-computer"]["mmh_prefix"] == "UAV1_", hv["uav1-computer"]
assert hv["uav2-computer"]["mmh_prefix"] == "UAV2_", hv["uav2-computer"]
assert hv["ground-station"]["mmh_prefix"] == ""
for inventory in (two, three):
    for host, v in inventory["_meta"]["hostvars"].items():
        assert "ttl=1" in v["mmh_lcm_url"], (host, v["mmh_lcm_url"])
h3 = three["_meta"]["hostvars"]
assert sorted(three["uav1"]["hosts"]) == ["ground", "planner", "vehicle"]
assert h3["planner"]["mmh_services"] == ["awareness", "fpm", "som", "eam", "arbiter"]
print("inventories: uav1 UAV1_, uav2 UAV2_, ground station without a prefix; ttl=1")
PY
# deploy.sh: a thin wrapper (--list-hosts runs nothing).
"$root/deploy/deploy.sh" restart som --list-hosts > "$out/wrap.txt" 2>&1 || { cat "$out/wrap.txt"; fail "deploy.sh"; }
grep -q "planner" "$out/wrap.txt" || { cat "$out/wrap.txt"; fail "deploy.sh restart som --list-hosts"; }
status=0
"$root/deploy/deploy.sh" reboot > /dev/null 2>&1 || status=$?
[ $status -eq 2 ] || fail "deploy.sh with an unknown action: exit code $status, not 2"
echo PASS
