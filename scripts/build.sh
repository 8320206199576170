#!/usr/bin/env bash
# Installs the dependencies (idempotent) and builds fleetmerge in ./build (Release).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
jobs=$(nproc 2>/dev/null || echo 2)
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DFLEETMERGE_BUILD_BENCHMARKS=ON "$@"
cmake --build build -j"$jobs"
