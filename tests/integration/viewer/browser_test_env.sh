# Sourced by the viewer's browser tests, with the build directory as their $1: skips (exit 77)
# without the page's npm packages, runs the test again inside a private network namespace, and
# sets root, web, out (a temporary directory; the test's trap removes it) and results
# (BUILD/test-output). cpu_ticks, cpu_share and cpu_guard measure mmh-viewer's CPU share.
build=$1
root=$(cd "$(dirname "$0")/../../.." && pwd)
web=$root/tools/viewer/web
if [ ! -x "$web/node_modules/.bin/esbuild" ] || ! command -v node >/dev/null; then
  echo "SKIP: the page's npm packages are not installed (deploy/setup.sh)"; exit 77
fi
if [ "${MMH_IN_NETNS:-0}" != 1 ]; then exec "$root/tests/integration/netns.sh" bash "$0" "$@"; fi
out=$(mktemp -d)
results=$build/test-output
mkdir -p "$results"

# CPU ticks (user + system) the process PID has used so far.
cpu_ticks() { awk '{ print $14 + $15 }' "/proc/$1/stat"; }
# Share of one core (%) of TICKS used over ELAPSED_NS of wall time.
cpu_share() {
  awk -v t="$1" -v hz="$(getconf CLK_TCK)" -v ns="$2" 'BEGIN { printf "%.1f", 100 * t / hz / (ns / 1e9) }'
}
# A guard against a runaway loop, not a timing figure (the machine is shared): under 25 %.
cpu_guard() { awk -v c="$1" 'BEGIN { exit !(c < 25) }'; }
