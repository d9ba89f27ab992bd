#!/usr/bin/env bash
# The package on a clean Debian 12, installed the way a user installs it, and the Debian 12 the
# three-host test boots (three_hosts.sh; a ctest fixture: this test runs first).
#   1. Once per build tree, $build/deploy-test/debian12: `debootstrap --variant=minbase bookworm`
#      with what a vehicle's computer runs anyway: systemd as init, dbus, openssh-server, and
#      python3 with python3-apt for Ansible. Nothing of the project's is in it.
#   2. In an overlay on it (in this test's own mount namespace): `apt-get install
#      --no-install-recommends ./mmh-planner_*.deb` resolves every dependency from Debian 12's
#      archive; then the install works: every /usr/bin/mmh-* finds its libraries, the installed
#      mmh-config-check reads /etc/mmh/mmh.yaml, the system user mmh owns /var/lib/mmh, the
#      unit template is where systemd looks; `dpkg --purge` takes the files and the conffile away.
#   3. What the package pulled in stays as a layer, $build/deploy-test/debian12-deps, for the
#      three hosts, which have no route to the archive.
# This test and setup.sh are the only ones that reach beyond the machine: Debian's archive
# (MMH_DEBIAN_MIRROR, default http://deb.debian.org/debian), for packages. Root only (chroot,
# mounts): exit code 77 is a skip.
set -euo pipefail
build=$(cd "$1" && pwd)
if [ "${MMH_DEBIAN12_NS:-0}" != 1 ]; then
  if [ "$(id -u)" -ne 0 ]; then echo "SKIP: needs root (debootstrap, chroot, mounts)"; exit 77; fi
  for tool in debootstrap cpack dpkg-deb unshare; do
    command -v "$tool" > /dev/null || { echo "FAIL: $tool missing: run deploy/setup.sh"; exit 1; }
  done
  MMH_DEBIAN12_NS=1 exec unshare --mount --propagation private bash "$0" "$@"
fi
mirror=${MMH_DEBIAN_MIRROR:-http://deb.debian.org/debian}
cache=$build/deploy-test
base=$cache/debian12
deps=$cache/debian12-deps
out=$(mktemp -d /tmp/mmh-debian12.XXXXXX)
trap 'umount -R "$out/merged" 2> /dev/null || true; rm -rf "$out" "$deps.new"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
started=$(date +%s)
step() { echo "== $(($(date +%s) - started)) s: $*"; }

if [ ! -f "$base/.complete" ]; then
  step "debootstrap bookworm into $base (once per build tree)"
  rm -rf "$base"
  mkdir -p "$cache"
  debootstrap --variant=minbase \
    --include=systemd,systemd-sysv,dbus,openssh-server,python3,python3-apt,iproute2 \
    bookworm "$base" "$mirror" > "$cache/debootstrap.log" 2>&1 ||
    { tail -20 "$cache/debootstrap.log"; fail "debootstrap (log: $cache/debootstrap.log)"; }
  touch "$base/.complete"
fi
grep -q 'VERSION_ID="12"' "$base/etc/os-release" || fail "$base is not Debian 12"
if chroot "$base" dpkg-query -W -f '${Package}\n' | grep -q '^mmh-planner$'; then
  fail "the clean Debian 12 has mmh-planner installed"
fi

step "the package"
cpack -G DEB -B "$out/pkg" --config "$build/CPackConfig.cmake" > "$out/cpack.log" 2>&1 ||
  { cat "$out/cpack.log"; fail "cpack -G DEB"; }
deb=$(ls "$out"/pkg/mmh-planner_*.deb)

step "apt-get install ./$(basename "$deb") on the clean Debian 12"
rm -rf "$deps.new"
mkdir -p "$deps.new" "$out/work" "$out/merged" "$cache/apt-archives/partial"
mount -t overlay overlay -o "lowerdir=$base,upperdir=$deps.new,workdir=$out/work" "$out/merged"
m=$out/merged
mount -t proc proc "$m/proc"
mount --rbind /dev "$m/dev"
mount -t tmpfs tmpfs "$m/tmp"
# Downloads are kept between runs of this build tree.
mount --bind "$cache/apt-archives" "$m/var/cache/apt/archives"
cp /etc/resolv.conf "$m/etc/resolv.conf"
echo "deb $mirror bookworm main" > "$m/etc/apt/sources.list"
cp "$deb" "$m/tmp/"
in_root() { chroot "$m" env -i PATH=/usr/sbin:/usr/bin:/sbin:/bin DEBIAN_FRONTEND=noninteractive "$@"; }
in_root apt-get update -q > "$out/apt.log" 2>&1 || { tail -20 "$out/apt.log"; fail "apt-get update"; }
in_root apt-get install -y -q --no-install-recommends "/tmp/$(basename "$deb")" >> "$out/apt.log" 2>&1 ||
  { tail -30 "$out/apt.log"; fail "apt-get install of the package on a clean Debian 12"; }
echo "installed with $(grep -c '^Setting up ' "$out/apt.log") packages in all"

step "the installed package works"
in_root dpkg-query -W -f '${Status}\n' mmh-planner | grep -qx 'install ok installed' ||
  fail "mmh-planner is not installed"
executables=$(ls "$m"/usr/bin/mmh-*)
[ "$(wc -l <<< "$executables")" -ge 10 ] || fail "too few executables: $executables"
for exe in $executables; do
  [ "$(head -c 4 "$exe" | tr -d '\0')" = $'\x7fELF' ] || continue
  missing=$(in_root ldd "${exe#"$m"}" | grep 'not found' || true)
  [ -z "$missing" ] || fail "$(basename "$exe") lacks libraries on a clean Debian 12: $missing"
done
in_root mmh-config-check > "$out/config.txt" 2>&1 || { cat "$out/config.txt"; fail "mmh-config-check"; }
grep -q /etc/mmh/mmh.yaml "$out/config.txt" || { cat "$out/config.txt"; fail "not /etc/mmh/mmh.yaml"; }
in_root getent passwd mmh > /dev/null || fail "no system user mmh"
[ "$(in_root stat -c %U /var/lib/mmh)" = mmh ] || fail "/var/lib/mmh not owned by mmh"
[ -f "$m/lib/systemd/system/mmh@.service" ] || fail "no mmh@.service where systemd looks"
[ -x "$m/usr/bin/lcm-logger" ] || fail "no lcm-logger (the logger service)"

step "dpkg --purge"
cp -a "$m/etc/mmh/mmh.yaml" "$out/mmh.yaml"
in_root dpkg --purge mmh-planner > "$out/purge.log" 2>&1 || { cat "$out/purge.log"; fail "purge"; }
[ ! -e "$m/usr/bin/mmh-arbiter" ] || fail "purge left /usr/bin/mmh-arbiter"
[ ! -e "$m/etc/mmh/mmh.yaml" ] || fail "purge left the conffile /etc/mmh/mmh.yaml"

# The layer for three_hosts.sh: Debian 12 with the package's dependencies, without the package
# or its user (the hosts' install makes them again).
in_root userdel mmh || fail "userdel mmh"
in_root groupdel mmh 2> /dev/null || true
rm -rf "$m/var/lib/mmh" "$m/etc/resolv.conf"
umount -R "$m"
rm -rf "$deps"
mv "$deps.new" "$deps"
step "done: $deps ($(du -sh "$deps" | cut -f1) over $(du -sh "$base" | cut -f1))"
echo PASS
