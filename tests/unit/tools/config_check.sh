#!/usr/bin/env bash
# mmh-config-check: the shipped file passes; a misspelt key fails with the nearest valid key,
# and an out-of-range value with the key and its range.
set -euo pipefail
build=$1
root=$(cd "$(dirname "$0")/../../.." && pwd)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

"$build/bin/mmh-config-check" "$root/deploy/config/default.yaml" >"$out/ok.txt" || fail "default.yaml rejected: $(cat "$out/ok.txt")"
grep -q ": OK$" "$out/ok.txt" || fail "no OK line"

sed 's/^  weight_corridor:/  weight_corridr:/; s/^  max_vel_mps: .*/  max_vel_mps: 120/' \
  "$root/deploy/config/default.yaml" >"$out/bad.yaml"
code=0
"$build/bin/mmh-config-check" "$out/bad.yaml" >"$out/bad.txt" || code=$?
[ $code -eq 1 ] || fail "bad file: exit $code (expected 1)"
grep -q "unknown key 'som.weight_corridr' in $out/bad.yaml (did you mean 'som.weight_corridor'?)" \
  "$out/bad.txt" || fail "no suggestion: $(cat "$out/bad.txt")"
grep -q "'vehicle.max_vel_mps' = 120 is outside the allowed range \[0.1, 50\]" "$out/bad.txt" ||
  fail "no range error: $(cat "$out/bad.txt")"
echo PASS
