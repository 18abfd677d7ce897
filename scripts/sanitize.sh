#!/usr/bin/env bash
# lodopt under AddressSanitizer + UndefinedBehaviorSanitizer (docs/robustness.md):
#   scripts/sanitize.sh            configures and builds build-asan, then runs the whole CTest suite
#   scripts/sanitize.sh build      configures and builds only
# Same compiler as the ordinary build (g++); -DLODOPT_SANITIZE=ON adds -fsanitize=address,undefined
# with -fno-sanitize-recover=undefined, so any report fails its test. Benchmarks are off.
# Environment: LODOPT_ASAN_BUILD_DIR (default build-asan), LODOPT_JOBS (default: all cores).
set -euo pipefail
cd "$(dirname "$0")/.."

mode=${1:-test}
case "$mode" in test|build) ;; *) echo "usage: scripts/sanitize.sh [test|build]" >&2; exit 2 ;; esac
build=${LODOPT_ASAN_BUILD_DIR:-build-asan}
jobs=${LODOPT_JOBS:-$(nproc)}

start=$(date +%s)
# -g1: line numbers in the reports, at a fraction of -g's compile time.
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS=-g1 \
  -DLODOPT_SANITIZE=ON -DLODOPT_BUILD_BENCH=OFF -DLODOPT_BUILD_TESTS=ON >/dev/null
cmake --build "$build" -j"$jobs"
echo "sanitize: $build built in $(( $(date +%s) - start )) s"
[ "$mode" = build ] && exit 0

# Leaks: only ours (tests/fuzz/lsan.supp lists the system libraries' own, with reasons).
suppressions="$PWD/tests/fuzz/lsan.supp"
export ASAN_OPTIONS="detect_leaks=1:strict_string_checks=1:check_initialization_order=1:detect_stack_use_after_return=1"
export LSAN_OPTIONS="suppressions=$suppressions:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
export CI=${CI:-1}
start=$(date +%s)
ctest --test-dir "$build" --output-on-failure -j2 --timeout 1800
echo "sanitize: the whole suite ran clean under ASan + UBSan in $(( $(date +%s) - start )) s"
