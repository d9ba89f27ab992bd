#!/usr/bin/env bash
# Installs (only when missing) every Debian 12 package MMH-Planner needs, then configures and
# builds the project with CMake (Release) into build/ (executables in build/bin/).
# Idempotent and quiet when everything is already there.
#
#   deploy/setup.sh              install what is missing, configure, build
#   deploy/setup.sh --no-build   install only
#   BUILD_DIR=build-asan CMAKE_ARGS="-DMMH_SANITIZE=ON" deploy/setup.sh   another build tree
#
# It also installs the npm packages of mmh-viewer's page (tools/viewer/web, npm ci from the
# committed package-lock.json), which the build bundles; nothing is fetched at run time.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build_dir=${BUILD_DIR:-$root/build}
case "$build_dir" in /*) ;; *) build_dir=$root/$build_dir ;; esac

packages=(
  build-essential cmake pkg-config git
  liblcm-dev liblcm-bin liblcm-java libjchart2d-java libglib2.0-dev
  libeigen3-dev liboctomap-dev libpcl-dev libnlopt-cxx-dev libyaml-cpp-dev
  libgtest-dev libbenchmark-dev nlohmann-json3-dev default-jdk-headless default-jre
  iproute2 util-linux procps python3 python3-matplotlib python3-numpy python3-yaml openssh-client
  openssh-server ansible python3-apt lintian fakeroot dpkg-dev file
  xvfb xauth x11-utils imagemagick clang clang-format libclang-rt-14-dev
  libwebsocketpp-dev libasio-dev chromium stress-ng debootstrap systemd-container
)
# Node.js and npm for mmh-viewer's page; a Node.js that already brings npm (e.g. a newer nodejs
# package that provides it) is kept.
command -v node >/dev/null || packages+=(nodejs)
command -v npm >/dev/null || packages+=(npm)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${#missing[@]} missing Debian packages: ${missing[*]}"
  sudo_cmd=()
  if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -qq
  "${sudo_cmd[@]}" apt-get install -y -qq "${missing[@]}" >/tmp/mmh-setup-apt.log 2>&1 || {
    tail -30 /tmp/mmh-setup-apt.log; echo "setup: apt-get install failed (log: /tmp/mmh-setup-apt.log)"; exit 1; }
fi

web=$root/tools/viewer/web
if [ ! -f "$web/node_modules/.package-lock.json" ] ||
   [ "$web/package-lock.json" -nt "$web/node_modules/.package-lock.json" ]; then
  echo "setup: installing the viewer page's npm packages (npm ci)"
  (cd "$web" && npm ci --no-audit --no-fund --loglevel=error) >/tmp/mmh-setup-npm.log 2>&1 || {
    tail -20 /tmp/mmh-setup-npm.log; echo "setup: npm ci failed (log: /tmp/mmh-setup-npm.log)"; exit 1; }
fi

[ "${1:-}" = "--no-build" ] && exit 0

jobs=$(nproc 2>/dev/null || echo 2)
if [ ! -f "$build_dir/CMakeCache.txt" ]; then
  cmake -S "$root" -B "$build_dir" -DCMAKE_BUILD_TYPE=Release ${CMAKE_ARGS:-} >"$build_dir.cmake.log" 2>&1 || {
    cat "$build_dir.cmake.log"; echo "setup: CMake configuration failed"; exit 1; }
fi
cmake --build "$build_dir" -j "$jobs" -- --no-print-directory >"$build_dir.build.log" 2>&1 || {
  grep -E "error|Error" -A3 "$build_dir.build.log" | head -60; echo "setup: build failed (log: $build_dir.build.log)"; exit 1; }
