#!/usr/bin/env bash
# The README's first command: set up, build, and run the main job on a built-in default.
# `fleetmerge demo` simulates 4 robots exploring a synthetic office (robot maps with the true
# answer), merges their maps, scores the merge against the truth and lists where the outputs are.
#
# Only what the demo needs: the command's packages (install_deps.sh --cli), a build without the
# tests, benchmarks and Python module, and only the `fleetmerge` target, as a unity build (each
# library's sources compiled a few at a time as one file: the headers of Eigen, OpenCV, Ceres and
# nlohmann-json are parsed once per batch, not once per file, which halves the compiler's CPU
# time). scripts/test.sh installs and builds the rest in the same build/ folder, file by file
# (scripts/build.sh turns the unity build off again: ccache and the tests work per file).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh --cli
jobs=$(nproc 2>/dev/null || echo 2)
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$PWD}  # as scripts/build.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DFLEETMERGE_BUILD_TESTS=OFF \
  -DFLEETMERGE_BUILD_BENCHMARKS=OFF -DFLEETMERGE_BUILD_PYTHON=OFF -DCMAKE_UNITY_BUILD=ON \
  "${launcher[@]}" "$@"
cmake --build build -j"$jobs" --target fleetmerge
out=out/demo
./build/cli/fleetmerge demo --out "$out"
echo
echo "open $out/case/merged/report.html in a browser to see the merge: maps, pose graph, every pair"
