#!/usr/bin/env bash
# The test command: installs what is missing, builds, and runs every test with ctest.
#   tests/run.sh               all tests
#   tests/run.sh -L unit       only unit tests (any ctest arguments are passed on)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/deploy/setup.sh"
cd "$root/build"
jobs=$(nproc 2>/dev/null || echo 2)
ctest --output-on-failure --timeout 1200 -j "$jobs" "$@"
