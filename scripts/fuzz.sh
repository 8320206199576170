#!/usr/bin/env bash
# CI stage: builds the libFuzzer targets (tests/fuzz) with clang + ASan + UBSan in build-fuzz/
# (scripts/sanitize_build.sh; already built by the sanitizer stage) and runs them side by side,
# each for FUZZ_SECONDS (default 40)
# from the seed corpus checked in under tests/fuzz/corpus (made from tests/data). Fails on any
# crash, sanitizer report, stray exception, timeout or memory blow-up. A failing input is saved
# in build-fuzz/findings/<target>/: fix the bug, then copy the input into
# tests/fuzz/regressions/<target>/ so that every ctest run replays it. A new fuzz target is one
# more name in `targets`.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${FUZZ_SECONDS:-40}"
targets=(map job octree bag cache)
bash scripts/sanitize_build.sh --target "${targets[@]/%/_fuzzer}"

export ASAN_OPTIONS="detect_leaks=1:halt_on_error=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
run() {  # one target; its exit status is the fuzzer's
  local t=$1
  local work="build-fuzz/corpus-run/$t"  # grows while fuzzing; the checked-in seeds stay as they are
  local findings="build-fuzz/findings/$t/"
  mkdir -p "$work" "$findings"
  cp -n tests/fuzz/corpus/"$t"/* "$work"/ 2>/dev/null || true
  ./build-fuzz/tests/fuzz/"$t"_fuzzer "$work" -max_total_time="$seconds" -timeout=10 \
    -rss_limit_mb=2048 -artifact_prefix="$findings" -print_final_stats=1 \
    >"build-fuzz/fuzz_$t.log" 2>&1
}
echo "fuzz: ${targets[*]} side by side for $seconds s"
pids=()
for t in "${targets[@]}"; do
  run "$t" &
  pids+=($!)
done
status=0
for k in "${!targets[@]}"; do
  t=${targets[$k]}
  log="build-fuzz/fuzz_$t.log"
  if ! wait "${pids[$k]}"; then
    status=1
    echo "fuzz: $t FAILED; input saved in build-fuzz/findings/$t/; last lines of $log:"
    tail -40 "$log"
  fi
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  echo "fuzz: $t: ${runs:-?} executions, corpus $(ls "build-fuzz/corpus-run/$t" | wc -l) inputs"
done
exit $status
