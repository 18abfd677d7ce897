#!/usr/bin/env bash
# Bounded libFuzzer runs of every fuzz target (docs/robustness.md):
#   scripts/fuzz.sh [SECONDS]     each target for SECONDS (default 60), under ASan + UBSan
# Configures build-fuzz with clang (libFuzzer needs it), builds only the fuzz targets
# (tests/fuzz: the glTF loader and the `lodopt metrics` input path, so only scenes, renderer and
# metrics are compiled), starts each from its checked-in seed corpus tests/fuzz/corpus/<target>/
# plus what earlier runs found (<build>/fuzz/<target>/corpus, never the source tree), and stops at
# the first crash, leak, timeout or out-of-memory. A finding is left in <build>/fuzz/<target>/;
# add it to tests/fuzz/regressions/<target>/ and fix the cause: the GoogleTest suites replay it.
# Environment: LODOPT_FUZZ_BUILD_DIR (default build-fuzz), LODOPT_JOBS (default: all cores),
# LODOPT_FUZZ_SEED (default 1; 0 = random).
set -euo pipefail
cd "$(dirname "$0")/.."

seconds=${1:-60}
case "$seconds" in ''|*[!0-9]*) echo "usage: scripts/fuzz.sh [SECONDS]" >&2; exit 2 ;; esac
build=${LODOPT_FUZZ_BUILD_DIR:-build-fuzz}
jobs=${LODOPT_JOBS:-$(nproc)}
for tool in clang clang++; do
  command -v "$tool" >/dev/null || { echo "fuzz: $tool not found (Debian: apt-get install clang libclang-rt-14-dev)" >&2; exit 1; }
done

start=$(date +%s)
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_CXX_FLAGS="-g1 -fsanitize=fuzzer-no-link" \
  -DLODOPT_SANITIZE=ON -DLODOPT_BUILD_BENCH=OFF -DLODOPT_BUILD_TESTS=ON -DLODOPT_BUILD_FUZZERS=ON >/dev/null
cmake --build "$build" -j"$jobs" --target fuzz_gltf fuzz_metrics_input
echo "fuzz: targets built in $(( $(date +%s) - start )) s"

suppressions="$PWD/tests/fuzz/lsan.supp"  # system libraries' own leaks, with reasons
export ASAN_OPTIONS="detect_leaks=1"
export LSAN_OPTIONS="suppressions=$suppressions:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"

# target  max_len  dictionary
targets=(
  "gltf 65536 tests/fuzz/gltf.dict"
  "metrics_input 16384 -"
)
status=0
for entry in "${targets[@]}"; do
  read -r target maxlen dict <<<"$entry"
  work="$build/fuzz/$target"
  mkdir -p "$work/corpus"
  # A fixed seed by default, so that CI explores the same inputs first on every run (a finding
  # reproduces); LODOPT_FUZZ_SEED=0 lets libFuzzer pick one.
  args=(-seed="${LODOPT_FUZZ_SEED:-1}" -max_total_time="$seconds" -max_len="$maxlen" -timeout=10 -rss_limit_mb=2048
        -print_final_stats=1 -artifact_prefix="$work/")
  [ "$dict" != - ] && args+=(-dict="$dict")
  echo "fuzz: $target for ${seconds} s"
  if ! "$build/tests/fuzz/fuzz_$target" "${args[@]}" "$work/corpus" "tests/fuzz/corpus/$target" \
       >"$work/log.txt" 2>&1; then
    status=1
    tail -n 60 "$work/log.txt" >&2
    echo "fuzz: $target found a problem; the input is in $work/ (crash-*, leak-*, timeout-* or oom-*)." >&2
    echo "fuzz: add it to tests/fuzz/regressions/$target/ and fix the cause (docs/robustness.md)." >&2
  else
    grep -E '^(stat::number_of_executed_units|stat::peak_rss_mb|#[0-9]+.*DONE)' "$work/log.txt" | sed "s/^/fuzz: $target: /" || true
  fi
done
exit $status
