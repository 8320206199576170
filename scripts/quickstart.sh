#!/usr/bin/env bash
# The README's first command: set up, build, and run the main job on a built-in default.
# `fleetmerge demo` simulates 4 robots exploring a synthetic office (robot maps with the true
# answer), merges their maps, scores the merge against the truth and lists where the outputs are.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
out=out/demo
./build/cli/fleetmerge demo --out "$out"
echo
echo "open $out/case/merged/report.html in a browser to see the merge: maps, pose graph, every pair"
