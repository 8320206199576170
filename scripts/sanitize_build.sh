#!/usr/bin/env bash
# Configures and builds build-fuzz/: clang with AddressSanitizer + UndefinedBehaviorSanitizer
# (no recovery), -O1, coverage instrumentation and the libFuzzer targets (FLEETMERGE_FUZZ), no
# benchmarks. One build serves both CI stages, the sanitizer test suite and the fuzzers: two
# builds of the whole tree do not fit CI's 25 minutes on 2 cores. No debug info by default (-g0:
# 15 % less compile time; reports name functions, not lines): FLEETMERGE_DEBUG_FLAGS=-g1 (or
# -g) for line numbers when chasing a report. A unity build (CMake compiles each target's
# sources in batches of 8 per compiler run, so Eigen, Ceres, OpenCV and GoogleTest are parsed
# once per batch rather than once per file; docs/architecture.md, CI, has the time it saves).
# scripts/test.sh still builds file by file, which catches a file that compiles only beside
# another; names that clash within a batch (two files' helpers of one name in anonymous
# namespaces) fail here.
# Idempotent.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc 2>/dev/null || echo 2)
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
cmake -S . -B build-fuzz -DCMAKE_CXX_COMPILER=clang++ -DFLEETMERGE_FUZZ=ON \
  -DFLEETMERGE_BUILD_BENCHMARKS=OFF -DCMAKE_BUILD_TYPE= -DCMAKE_UNITY_BUILD=ON \
  -DCMAKE_CXX_FLAGS="-O1 ${FLEETMERGE_DEBUG_FLAGS:--g0}" \
  "${launcher[@]}"
cmake --build build-fuzz -j"$jobs" "$@"
