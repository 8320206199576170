#!/usr/bin/env bash
# The README's second command: set up, build, and run the whole test suite with ctest.
# Tests that need the real maps in ../shared/data/maps skip with a message when it is absent.
set -euo pipefail
cd "$(dirname "$0")/.."
# The benchmarks are not tests: CI does not build them (scripts/build.sh does).
bash scripts/build.sh -DFLEETMERGE_BUILD_BENCHMARKS=OFF "$@"
jobs=$(nproc 2>/dev/null || echo 2)
ctest --test-dir build --output-on-failure -j"$jobs"
