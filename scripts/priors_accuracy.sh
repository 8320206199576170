#!/usr/bin/env bash
# Known start poses on every real building in ../shared (issue 22's "priors off by 0.3 m and
# 5 deg with sigma (0.5 m, 10 deg): every pair right"): per building and seed, `fleetmerge
# simulate` 5 robots (simulate's default 50 m paths) four times, the same robots each time:
# without priors, with `--priors 0.3,5` (each robot's initial_pose 0.3 m and 5 deg off its true
# pose), with `--fixed-base` (the building's map as the site's fixed base) and with both. Each is
# merged and scored by `eval`. Per variant: the cases, the truly overlapping pairs, coarse, fine,
# cases with false merges, maps placed by their prior, missed maps, and the median displacement
# (cells) of the pairs merged in the variant without priors and in this one; then each priors
# variant against its variant without priors, pair by pair (better / worse by 0.01 cells).
# Needs a build (scripts/build.sh) and ../shared/data/maps; about 1.5 minutes on 2 cores.
# Usage: scripts/priors_accuracy.sh [OUT_DIR]   (default out/priors_accuracy)
# PRIORS_SEEDS replaces the seed list (default 1 2).
set -euo pipefail
cd "$(dirname "$0")/.."
FIXED_BASE_SEEDS=${PRIORS_SEEDS:-1 2}
source scripts/fixed_base_cases.sh priors_accuracy "${1:-out/priors_accuracy}"

declare -A variant_options=(
  [none]="" [priors]="--priors 0.3,5" [base]="--fixed-base" [base_priors]="--fixed-base --priors 0.3,5")
for variant in none priors base base_priors; do
  for building in $buildings; do
    for seed in $seeds; do
      dir=$out/$variant/${building}_$seed
      rm -rf "$dir"
      # shellcheck disable=SC2086  # the options are words
      "$fleetmerge" simulate "$dir" --building "$maps/$building.yaml" --robots 5 --seed "$seed" \
        ${variant_options[$variant]} >/dev/null
      "$fleetmerge" merge --quiet "$dir/job.yaml" >/dev/null
      "$fleetmerge" eval --json "$dir/merged/report.json" "$dir/truth.yaml" >"$dir/eval.json"
    done
  done
done

/usr/bin/python3 - "$out" <<'PY'
import glob, json, os, statistics, sys
out = sys.argv[1]

def cases(variant):
    for d in sorted(glob.glob(os.path.join(out, variant, "*"))):
        yield os.path.basename(d), json.load(open(os.path.join(d, "eval.json"))), \
            json.load(open(os.path.join(d, "merged", "report.json")))

def merged_pairs(evaluation):
    return {(p["a"], p["b"]): p["displacement_cells"] for p in evaluation["pairs"]
            if p["scored"] and p["merged"]}

for variant, plain in (("none", None), ("priors", "none"), ("base", None),
                       ("base_priors", "base")):
    n = scored = coarse = fine = false = prior = missed = 0
    for name, e, report in cases(variant):
        s = e["summary"]
        n += 1
        scored += s["scored_pairs"]; coarse += s["coarse_pairs"]; fine += s["fine_pairs"]
        false += s["false_merges"] > 0
        missed += len(s["missed_maps"]) if isinstance(s["missed_maps"], list) else s["missed_maps"]
        prior += sum(m["placed_by"] == "prior" for m in report["maps"])
    line = (f"{variant}: {n} cases, {scored} truly overlapping pairs; coarse {coarse}, fine {fine}; "
            f"{false} cases with false merges; {prior} maps placed by their prior; {missed} missed")
    if plain:
        a, b, better, worse = [], [], 0, 0
        plain_cases = {name: e for name, e, _ in cases(plain)}
        for name, e, _ in cases(variant):
            without, with_priors = merged_pairs(plain_cases[name]), merged_pairs(e)
            for pair in without.keys() & with_priors.keys():
                a.append(without[pair]); b.append(with_priors[pair])
                better += b[-1] < a[-1] - 0.01
                worse += b[-1] > a[-1] + 0.01
        line += (f"; {len(a)} pairs merged in both: median displacement {statistics.median(a):.3f}"
                 f" -> {statistics.median(b):.3f} cells, {better} better, {worse} worse than {plain}")
    print(line)
PY
