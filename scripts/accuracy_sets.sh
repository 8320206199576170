#!/usr/bin/env bash
# Every simulated accuracy set outside ctest, one after another: the rows of docs/accuracy.md's
# table besides the ctest suite (held-out, fresh, seeds 51-54 / 61-68, foreign, look-alike).
# A change that can move a pose runs all of them, not a subset: a one-pair drop on one set does
# not show on the others. About 6 minutes on 2 cores. Needs a build (scripts/build.sh) and
# ../shared/data/maps. Usage: scripts/accuracy_sets.sh [OUT_DIR]   (default out/accuracy_sets)
# Writes each set's per-case lines to OUT_DIR/<set>.txt and prints the table's rows.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-out/accuracy_sets}
mkdir -p "$out"

run_set() {  # name, script, then VAR=value settings for it
  local name=$1 script=$2
  shift 2
  env "$@" bash "$script" "$out/$name" >"$out/$name.txt"
  local total
  total=$(tail -n 1 "$out/$name.txt")
  echo "$name: ${total#*: }"  # the set's name instead of the script's
}

run_set held-out scripts/heldout_accuracy.sh
run_set fresh scripts/heldout_accuracy.sh HELDOUT_SEEDS_A="41 42" HELDOUT_SEEDS_B="31 32 33 34"
run_set seeds51-68 scripts/heldout_accuracy.sh HELDOUT_SEEDS_A="51 52 53 54" \
  HELDOUT_SEEDS_B="61 62 63 64 65 66 67 68"
run_set foreign scripts/lookalike_accuracy.sh
run_set look-alike scripts/lookalike_accuracy.sh LOOKALIKE_SEEDS="$(seq 115 164 | tr '\n' ' ')" \
  LOOKALIKE_KINDS="office office_little"
