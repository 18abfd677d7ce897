#!/usr/bin/env bash
# lodopt quick start: installs what is missing (Debian 12, as root), builds, then
#   scripts/quickstart.sh run   runs the main job on the built-in default scene
#   scripts/quickstart.sh test  runs the whole test suite through CTest
# Idempotent: packages already installed are not touched, the build is incremental.
set -euo pipefail
cd "$(dirname "$0")/.."

mode=${1:-run}
case "$mode" in run|test) ;; *) echo "usage: scripts/quickstart.sh run|test" >&2; exit 2 ;; esac

packages=(
  cmake ninja-build g++ pkg-config
  libosmesa6-dev libopencv-dev libopenimageio-dev openimageio-tools
  libglm-dev libtinygltf-dev libstb-dev nlohmann-json3-dev libmeshoptimizer-dev libcli11-dev
  libgtest-dev libgmock-dev libbenchmark-dev gnuplot-nox
)
missing=()
for package in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" || missing+=("$package")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "quickstart: installing ${missing[*]}"
  sudo=""
  if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

build=${LODOPT_BUILD_DIR:-build}
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" -j"$(nproc)"

if [ "$mode" = run ]; then
  out=${LODOPT_OUT:-out/quickstart}
  "$build"/cli/lodopt render --scene harbor --view overview --out "$out/harbor_reference.png"
  "$build"/cli/lodopt render --scene harbor --view overview --levels 5,4,4 --out "$out/harbor_coarse.png"
  echo "quickstart: images are in $out/"
else
  ctest --test-dir "$build" --output-on-failure -j2 --timeout 900
fi
