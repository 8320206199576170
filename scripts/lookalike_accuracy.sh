#!/usr/bin/env bash
# Fleets with one robot from another building, many of them a look-alike synthetic office: the
# cases behind docs/accuracy.md's "Lone links". Needs a build (scripts/build.sh) and
# ../shared/data/maps. Usage: scripts/lookalike_accuracy.sh [OUT_DIR]
# LOOKALIKE_SEEDS (default "100 ... 114") and LOOKALIKE_KINDS (default "office office_little
# stata_intel gdc_floors") choose the cases; 4 robots each, 100 m of path. Prints one line per case
# (pairs, coarse, fine, false merges), then the cases with a false merge and the totals.
# scripts/bridges.py OUT_DIR/* lists every accepted bridge edge with its walls and the truth.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/simulated_cases.sh lookalike_accuracy "${1:-out/lookalike}"

{
  for seed in ${LOOKALIKE_SEEDS:-$(seq 100 114)}; do
    for kind in ${LOOKALIKE_KINDS:-office office_little stata_intel gdc_floors}; do
      case $kind in
        office)
          run_case "office_$seed" --robots 4 --seed "$seed" \
            --foreign-office-seed $((seed + 1000)) ;;
        office_little)
          run_case "office_little_$seed" --robots 4 --seed "$seed" --little-overlap \
            --foreign-office-seed $((seed + 1000)) ;;
        stata_intel)
          run_case "stata_intel_$seed" --robots 4 --seed "$seed" \
            --building "$maps/stata_basement.yaml" --foreign "$maps/intel_lab.yaml" ;;
        gdc_floors)
          run_case "gdc_floors_$seed" --robots 4 --seed "$seed" \
            --building "$maps/gdc_floor1_full.yaml" --foreign "$maps/gdc_floor2_full.yaml" ;;
        *) echo "lookalike_accuracy: unknown kind '$kind'" >&2; exit 1 ;;
      esac
    done
  done
} | tee "$out/summary.txt"
awk '$5 > 0 {print "false merge:", $1}' "$out/summary.txt"
awk '{p += $2; c += $3; f += $4; m += $5; n++; bad += ($5 > 0)}
     END {printf "look-alike: %d cases, %d truly overlapping pairs; coarse %d, fine %d; %d cases with false merges (%d pairs)\n",
          n, p, c, f, bad, m}' "$out/summary.txt"
