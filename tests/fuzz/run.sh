#!/usr/bin/env bash
# Bounded libFuzzer run over every LCM message decoder + validator (tests/fuzz/): configures and
# builds the fuzz tree (clang, -DMMH_FUZZ=ON, ASan + UBSan) in build-fuzz/, then runs each target
# for a fixed time on its seed corpus (tests/fuzz/corpus/<type>/, never modified; new inputs go
# to build-fuzz/fuzz-work/<type>/). A crash, a leak, UB, a timeout or an out-of-memory fails the
# run and leaves the input in build-fuzz/fuzz-artifacts/.
#
#   tests/fuzz/run.sh                         every target, 15 s each (ctest test fuzz_messages)
#   tests/fuzz/run.sh --seconds 600 --target local_map_t
# Exit codes: 0 clean, 1 a finding or a build failure, 77 clang/libFuzzer not installed (skip).
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
seconds=${MMH_FUZZ_SECONDS:-15}
build_dir=${MMH_FUZZ_BUILD_DIR:-$root/build-fuzz}
targets=()
while [ $# -gt 0 ]; do
  case "$1" in
    --seconds) seconds=$2; shift 2 ;;
    --target) targets+=("$2"); shift 2 ;;
    --build-dir) build_dir=$2; shift 2 ;;
    -h|--help) sed -n '2,11p' "$0"; exit 0 ;;
    *) echo "fuzz: unknown option $1" >&2; exit 2 ;;
  esac
done
[ ${#targets[@]} -gt 0 ] || targets=(odometry_t pointcloud_t goal_t local_map_t awareness_t
  trajectory_t plan_request_t plan_result_t arbiter_status_t heartbeat_t mission_status_t
  setpoint_t plan_debug_t)

if ! command -v clang++ >/dev/null || ! ls /usr/lib/llvm-*/lib/clang/*/lib/linux/libclang_rt.fuzzer-x86_64.a >/dev/null 2>&1; then
  echo "fuzz: clang++ or libFuzzer (libclang-rt-*-dev) missing: skipped"
  exit 77
fi

if [ ! -f "$build_dir/CMakeCache.txt" ]; then
  CC=clang CXX=clang++ cmake -S "$root" -B "$build_dir" -DMMH_FUZZ=ON -DCMAKE_BUILD_TYPE=Release \
    >"$build_dir.cmake.log" 2>&1 || { cat "$build_dir.cmake.log"; echo "fuzz: configure failed"; exit 1; }
fi
cmake --build "$build_dir" -j 2 -- --no-print-directory >"$build_dir.build.log" 2>&1 || {
  grep -E "error" -A3 "$build_dir.build.log" | head -40; echo "fuzz: build failed (log: $build_dir.build.log)"; exit 1; }

artifacts=$build_dir/fuzz-artifacts
mkdir -p "$artifacts"
failed=0
for t in "${targets[@]}"; do
  seeds=$root/tests/fuzz/corpus/$t
  work=$build_dir/fuzz-work/$t
  log=$build_dir/fuzz-$t.log
  mkdir -p "$work"
  # -timeout: one input may take at most 10 s; -rss_limit_mb/-malloc_limit_mb: memory bombs fail.
  if ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
     "$build_dir/bin/fuzz_$t" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
       -malloc_limit_mb=1024 -print_final_stats=1 -artifact_prefix="$artifacts/$t-" \
       "$work" "$seeds" >"$log" 2>&1; then
    execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
    cov=$(grep -Eo 'cov: [0-9]+' "$log" | tail -1)
    printf 'fuzz %-18s ok   %8s runs in %ss, %s, corpus %s\n' "$t" "${execs:-?}" "$seconds" \
      "${cov:-cov: ?}" "$(ls "$work" | wc -l)"
  else
    failed=1
    printf 'fuzz %-18s FAILED (log %s)\n' "$t" "$log"
    grep -E "ERROR|runtime error|SUMMARY|invariant|Test unit written" "$log" | head -12
  fi
done
exit $failed
