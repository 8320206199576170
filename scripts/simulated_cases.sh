# Sourced by scripts/heldout_accuracy.sh, scripts/lookalike_accuracy.sh and
# scripts/fixed_base_cases.sh (from the repository root): simulated cases merged with the build's
# fleetmerge and scored against their truth.
# Usage: source scripts/simulated_cases.sh SCRIPT_NAME OUT_DIR
# Sets fleetmerge (BUILD_DIR's, default build), maps and out, and defines run_case NAME
# SIMULATE_OPTIONS..., which prints one line: name, truly overlapping pairs, coarse, fine, false
# merges.
fleetmerge=${BUILD_DIR:-build}/cli/fleetmerge
maps=../shared/data/maps
out=$2
if [ ! -d "$maps" ]; then
  echo "$1: $maps is missing (the real building maps)" >&2
  exit 1
fi
mkdir -p "$out"

run_case() {  # name, then `fleetmerge simulate` options
  local name=$1 dir=$out/$1
  shift
  rm -rf "$dir"
  "$fleetmerge" simulate "$dir" --path-length 100 "$@" >/dev/null
  "$fleetmerge" merge "$dir/job.yaml" --quiet >/dev/null
  "$fleetmerge" eval "$dir/merged/report.json" "$dir/truth.yaml" --json >"$dir/eval.json"
  python3 - "$name" "$dir/eval.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[2]))["summary"]
print(sys.argv[1], s["scored_pairs"], s["coarse_pairs"], s["fine_pairs"], s["false_merges"])
PY
}
