#!/usr/bin/env bash
# Gate: every C++ file the repository tracks is formatted as .clang-format says
# (clang-format --dry-run --Werror). Fix with:
#   git ls-files '*.cpp' '*.hpp' '*.h' '*.cc' | xargs clang-format -i
# $1: the clang-format binary (CMake's find_program; empty when none was found).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
clang_format=${1:-}
if [ -z "$clang_format" ] || ! command -v "$clang_format" >/dev/null 2>&1; then
  echo "FAIL: clang-format not found. Install Debian's clang-format package (deploy/setup.sh" \
    "does), then re-run cmake so that it finds /usr/bin/clang-format."
  exit 1
fi
cd "$root"
mapfile -t files < <(git ls-files '*.cpp' '*.hpp' '*.h' '*.cc')
[ ${#files[@]} -gt 0 ] || { echo "FAIL: no C++ files found below $root (not a git checkout?)"; exit 1; }
if ! "$clang_format" --dry-run --Werror "${files[@]}" 2>/tmp/mmh-format-check.$$; then
  grep -E "^[^ ].*: (error|warning):" /tmp/mmh-format-check.$$ | cut -d: -f1 | sort -u |
    sed 's/^/  not formatted: /'
  rm -f /tmp/mmh-format-check.$$
  echo "FAIL: run clang-format -i on the files above ($("$clang_format" --version))"
  exit 1
fi
rm -f /tmp/mmh-format-check.$$
echo "PASS: ${#files[@]} C++ files formatted ($("$clang_format" --version))"
