#!/usr/bin/env bash
# CI stage: the whole test suite built with AddressSanitizer + UndefinedBehaviorSanitizer (clang,
# -O1, no benchmarks; scripts/sanitize_build.sh) in build-fuzz/. Every test runs; the heavy
# accuracy tests run a reduced number of trials (FLEETMERGE_TEST_SCALE). Any sanitizer report
# fails its test (no recovery).
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc 2>/dev/null || echo 2)
bash scripts/sanitize_build.sh
# detect_leaks: OpenCV's and Ceres's process-lifetime singletons are not leaks we can fix, but
# our own are: leak checking stays on. halt_on_error: the first report fails the test.
export ASAN_OPTIONS="halt_on_error=1:detect_leaks=1:abort_on_error=0"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
export FLEETMERGE_TEST_SCALE="${FLEETMERGE_TEST_SCALE:-0.06}"
ctest --test-dir build-fuzz --output-on-failure -j"$jobs"
