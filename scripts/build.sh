#!/usr/bin/env bash
# Installs the dependencies (idempotent) and builds fleetmerge in ./build (Release).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
jobs=$(nproc 2>/dev/null || echo 2)
# ccache (installed by install_deps.sh) lets a second build of the same sources (another build
# folder, a colcon workspace, a package build) reuse the objects of the first.
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$PWD}  # compile commands under the repository hash alike
# Tests and the Python module on, and the unity build off, explicitly: scripts/quickstart.sh
# configures the same folder with them off and it on.
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DFLEETMERGE_BUILD_TESTS=ON -DFLEETMERGE_BUILD_PYTHON=ON \
  -DFLEETMERGE_BUILD_BENCHMARKS=ON -DCMAKE_UNITY_BUILD=OFF "${launcher[@]}" "$@"
cmake --build build -j"$jobs"
