#!/usr/bin/env bash
# Accuracy on simulated fleets that the ctest suite does not use (other seeds, harder options):
# the held-out check behind docs/accuracy.md's "Accuracy suite" numbers. Needs a build
# (scripts/build.sh) and ../shared/data/maps. Usage: scripts/heldout_accuracy.sh [OUT_DIR]
# Prints one line per case (pairs, coarse, fine, false merges) and the totals.
# HELDOUT_SEEDS_A / HELDOUT_SEEDS_B replace the two seed lists (default "11 12" and
# "21 22 23 24"): other seeds give a fresh set of the same kinds of cases, for a choice made while
# looking at these.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/simulated_cases.sh heldout_accuracy "${1:-out/heldout}"

{
  for seed in ${HELDOUT_SEEDS_A:-11 12}; do
    run_case "gdc_$seed" --building "$maps/gdc_floor1_full.yaml" --robots 5 --seed $seed
    run_case "csail_$seed" --building "$maps/mit_csail.yaml" --robots 5 --seed $seed
    run_case "stata_$seed" --building "$maps/stata_basement.yaml" --robots 5 --seed $seed
    run_case "aces_$seed" --building "$maps/aces3_austin.yaml" --robots 5 --seed $seed
    run_case "intel_$seed" --building "$maps/intel_lab.yaml" --robots 5 --seed $seed
    run_case "office_little_$seed" --robots 5 --seed $seed --little-overlap
  done
  for seed in ${HELDOUT_SEEDS_B:-21 22 23 24}; do
    run_case "gdc_$seed" --building "$maps/gdc_floor1_full.yaml" --robots 5 --seed $seed
    run_case "csail_$seed" --building "$maps/mit_csail.yaml" --robots 5 --seed $seed
    run_case "stata_foreign_$seed" --building "$maps/stata_basement.yaml" --robots 4 \
      --seed $seed --foreign "$maps/intel_lab.yaml"
    run_case "office_little_foreign_$seed" --robots 4 --seed $seed --little-overlap \
      --foreign-office-seed $((seed + 1000))
    run_case "b31_$seed" --building "$maps/mit_building_31.yaml" --robots 6 --seed $seed
  done
} | tee "$out/summary.txt"
awk '{p += $2; c += $3; f += $4; m += $5}
     END {printf "held-out: %d truly overlapping pairs; coarse %d (%.1f %%), fine %d (%.1f %%); false merges %d\n",
          p, c, 100 * c / p, f, 100 * f / p, m}' "$out/summary.txt"
