#!/usr/bin/env bash
# CI stage: builds the libFuzzer targets (tests/fuzz) with clang + ASan + UBSan in build-fuzz/
# and runs each for FUZZ_SECONDS (default 40: the three targets take about 2 minutes together)
# from the seed corpus checked in under tests/fuzz/corpus (made from tests/data). Fails on any
# crash, sanitizer report, stray exception, timeout or memory blow-up. A failing input is saved
# in build-fuzz/findings/<target>/: fix the bug, then copy the input into
# tests/fuzz/regressions/<target>/ so that every ctest run replays it. A new fuzz target is one
# more name in `targets`.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${FUZZ_SECONDS:-40}"
targets=(map job octree)
jobs=$(nproc 2>/dev/null || echo 2)
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
cmake -S . -B build-fuzz -DCMAKE_CXX_COMPILER=clang++ -DFLEETMERGE_FUZZ=ON \
  -DFLEETMERGE_BUILD_BENCHMARKS=OFF -DCMAKE_BUILD_TYPE= -DCMAKE_CXX_FLAGS="-O1 -g" "${launcher[@]}"
cmake --build build-fuzz -j"$jobs" --target "${targets[@]/%/_fuzzer}"

export ASAN_OPTIONS="detect_leaks=1:halt_on_error=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
status=0
for t in "${targets[@]}"; do
  work="build-fuzz/corpus-run/$t"      # grows while fuzzing; the checked-in seeds stay as they are
  findings="build-fuzz/findings/$t/"
  mkdir -p "$work" "$findings"
  cp -n tests/fuzz/corpus/"$t"/* "$work"/ 2>/dev/null || true
  log="build-fuzz/fuzz_$t.log"
  echo "fuzz: $t for $seconds s"
  if ! ./build-fuzz/tests/fuzz/"$t"_fuzzer "$work" -max_total_time="$seconds" -timeout=10 \
      -rss_limit_mb=2048 -artifact_prefix="$findings" -print_final_stats=1 >"$log" 2>&1; then
    status=1
    echo "fuzz: $t FAILED; input saved in $findings; last lines of $log:"
    tail -40 "$log"
  fi
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  echo "fuzz: $t: ${runs:-?} executions, corpus $(ls "$work" | wc -l) inputs"
done
exit $status
