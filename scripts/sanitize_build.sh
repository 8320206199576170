#!/usr/bin/env bash
# Configures and builds build-fuzz/: clang with AddressSanitizer + UndefinedBehaviorSanitizer
# (no recovery), -O1, coverage instrumentation and the libFuzzer targets (FLEETMERGE_FUZZ), no
# benchmarks. One build serves both CI stages, the sanitizer test suite and the fuzzers: two
# builds of the whole tree do not fit CI's 25 minutes on 2 cores. No debug info by default (-g0:
# 15 % less compile time; reports name functions, not lines): FLEETMERGE_DEBUG_FLAGS=-g1 (or
# -g) for line numbers when chasing a report. Idempotent.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc 2>/dev/null || echo 2)
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
cmake -S . -B build-fuzz -DCMAKE_CXX_COMPILER=clang++ -DFLEETMERGE_FUZZ=ON \
  -DFLEETMERGE_BUILD_BENCHMARKS=OFF -DCMAKE_BUILD_TYPE= \
  -DCMAKE_CXX_FLAGS="-O1 ${FLEETMERGE_DEBUG_FLAGS:--g0}" \
  "${launcher[@]}"
cmake --build build-fuzz -j"$jobs" "$@"
