#!/usr/bin/env bash
# lodopt quick start: installs what is missing (Debian 12, as root), builds, then
#   scripts/quickstart.sh run   runs the main job on the built-in default scene
#   scripts/quickstart.sh test  runs the whole test suite through CTest, then again under
#                               ASan + UBSan (scripts/sanitize.sh) and fuzzes (scripts/fuzz.sh);
#                               LODOPT_SKIP_SANITIZERS=1 runs only the first
# Idempotent: packages already installed are not touched, the build is incremental.
set -euo pipefail
cd "$(dirname "$0")/.."

mode=${1:-run}
case "$mode" in run|test) ;; *) echo "usage: scripts/quickstart.sh run|test" >&2; exit 2 ;; esac

packages=(
  cmake ninja-build g++ pkg-config
  libosmesa6-dev libegl-dev libegl-mesa0 libopencv-dev libpng-dev libjpeg-dev libopenexr-dev
  libglm-dev libtinygltf-dev libstb-dev nlohmann-json3-dev libmeshoptimizer-dev libcli11-dev libdraco-dev libwebp-dev
  libjxl-dev libjxl-devtools
  libpagmo-dev openmpi-bin libopenmpi-dev
  libgtest-dev libgmock-dev libbenchmark-dev gnuplot-nox
  clang libclang-rt-14-dev ccache
)
missing=()
for package in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" || missing+=("$package")
done
# The test harnesses (tests/harness, docs/harness.md; `test` only): Node with npm, Chromium for the
# three.js reference renders, and their npm packages (pinned by package-lock.json). A node already
# on the PATH is kept with its own npm: Debian's npm would pull in Debian's nodejs over it.
if [ "$mode" = test ]; then
  command -v node >/dev/null || missing+=(nodejs npm)
  command -v chromium >/dev/null || missing+=(chromium)
fi
if [ ${#missing[@]} -gt 0 ]; then
  echo "quickstart: installing ${missing[*]}"
  sudo=""
  if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
if [ "$mode" = test ]; then
  command -v npm >/dev/null || { echo "quickstart: node is installed without npm; install npm for it" >&2; exit 1; }
  if [ ! -d tests/harness/node_modules ] || [ tests/harness/package-lock.json -nt tests/harness/node_modules ]; then
    echo "quickstart: npm ci --prefix tests/harness"
    npm ci --prefix tests/harness --no-audit --no-fund >/dev/null
    touch tests/harness/node_modules
  fi
fi

# ccache (CMakeLists.txt uses it when found): paths relative to the checkout, so a fresh clone in
# another folder (CI) hits what an earlier build here compiled; -g1 builds ignore the folder too.
export CCACHE_BASEDIR="$PWD" CCACHE_NOHASHDIR=1

# Each stage's wall time, printed at the end of a test run (where CI's time goes).
stages=()
stage_start=$(date +%s)
stage_done() {
  local now
  now=$(date +%s)
  stages+=("$1 $((now - stage_start)) s")
  stage_start=$now
}
stage_done "install"

build=${LODOPT_BUILD_DIR:-build}
# LODOPT_PAGMO=ON, LODOPT_MPI=ON: the pagmo:* algorithms (libpagmo-dev) and the sweep under mpirun
# (libopenmpi-dev), both installed above, must be built.
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DLODOPT_PAGMO=ON -DLODOPT_MPI=ON >/dev/null
cmake --build "$build" -j"$(nproc)"
stage_done "build"

if [ "$mode" = run ]; then
  out=${LODOPT_OUT:-out/quickstart}
  # The main job: the best LOD combination of the default scene under a 7 ms budget
  # (tests/cli: QuickStart.MainJobRuns runs this line).
  "$build"/cli/lodopt optimize --scene harbor --view overview --budget-ms 7 --seed 1 --out "$out"
  echo "quickstart: result.json, curve.csv, optimized.png and reference.png are in $out/"
else
  ctest --test-dir "$build" --output-on-failure -j2 --timeout 900
  stage_done "ctest"
  # Then the same suite under ASan + UBSan (build-asan) and bounded fuzzing of every fuzz
  # target (docs/robustness.md). LODOPT_SKIP_SANITIZERS=1 skips both for a quick local run.
  if [ "${LODOPT_SKIP_SANITIZERS:-0}" != 1 ]; then
    scripts/sanitize.sh
    stage_done "sanitizers (build and suite)"
    scripts/fuzz.sh "${LODOPT_FUZZ_SECONDS:-60}"
    stage_done "fuzzing (build and runs)"
  fi
  echo "quickstart: stage times: $(IFS=';'; echo "${stages[*]}" | sed 's/;/, /g')"
fi
