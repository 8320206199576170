#!/usr/bin/env bash
# The README's first command: set up, build, and run the main job on a built-in default.
# It writes a synthetic two-robot example with a known answer, merges it with `fleetmerge pair`,
# and prints the ranked hypotheses next to the truth.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
out=out/quickstart
rm -rf "$out"
./build/pipeline/fleetmerge example "$out/maps"
./build/pipeline/fleetmerge pair "$out/maps/robot_a.yaml" "$out/maps/robot_b.yaml" --out "$out/merged"
echo
echo "truth: $out/maps/truth.yaml; open $out/merged/merged_preview.png to see the merged map"
