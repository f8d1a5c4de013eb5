#!/usr/bin/env bash
# IPD Studio: one command to set up, build and run.
#   ./run.sh        install what is missing, build, run the main job on the built-in demo study
#   ./run.sh test   install what is missing, build, run every test (ctest)
set -euo pipefail
cd "$(dirname "$0")"

packages=(
  cmake g++ make pkg-config ccache
  libopencv-core-dev libopencv-imgproc-dev libopencv-imgcodecs-dev libopencv-dnn-dev python3-onnx
  libeigen3-dev libssl-dev libyaml-cpp-dev nlohmann-json3-dev libcli11-dev libfmt-dev libgtest-dev
  python3-numpy
  libimgui-dev libglfw3-dev libgl-dev libosmesa6-dev libstb-dev fonts-dejavu-core xvfb xauth
  libcairo2-dev libharfbuzz-dev libpolyclipping-dev python3-shapely poppler-utils desktop-file-utils imagemagick
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "Installing: ${missing[*]}"
  sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

jobs=$(nproc 2>/dev/null || echo 2)
# Every build goes through ccache: a rebuild of the same sources (another build directory, another clone of the
# project, a CI run after a local build) compiles only what changed. CCACHE_BASEDIR makes the paths in the
# compiler commands relative to the clone, so clones at different paths share the cache.
export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$PWD}"
# A first build compiles the product as a unity build (a batch of files per compiler run: their shared headers
# parsed once, most of a cold build's time). An existing build directory keeps its own setting, so a developer
# who turned it off (-DCMAKE_UNITY_BUILD=OFF, one file per run for quick rebuilds) keeps it off.
unity=()
[ -f build/CMakeCache.txt ] || unity=(-DCMAKE_UNITY_BUILD=ON)
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache \
  "${unity[@]}" >/dev/null
cmake --build build -j"$jobs"

if [ "${1:-}" = "test" ]; then
  exec ctest --test-dir build --output-on-failure -j"$jobs"
fi

demo=build/demo-study
[ -f "$demo/study.yaml" ] || ./build/app/ipd demo "$demo"
if [ -x build/app/ipd-studio ] && [ -n "${DISPLAY:-}${WAYLAND_DISPLAY:-}" ]; then
  exec ./build/app/ipd-studio "$demo"
fi
echo
echo "IPD cross table of the demo study (rows: detector and its training domain; lower is better):"
./build/app/ipd table "$demo"
echo
echo "Picture of the scene that contributes most to IPD(real, principled):"
./build/app/ipd figure pairs "$demo" --out build/demo-scene.png --column double
