#!/usr/bin/env bash
# Rebuilds the checked-in MCAP bags mcap_sim_seed3/robot{1,2,3}: the fleet of
# `fleetmerge simulate --robots 3 --seed 3`, robot1 zstd chunks, robot2 lz4, robot3 uncompressed
# (2 messages, to stay small). Needs node + npm (npm ci here) and the zstd and lz4 tools.
# Usage: tests/data/bags/make_mcap_fixtures.sh build/cli/fleetmerge
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
fleetmerge="$(realpath "$1")"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
"$fleetmerge" simulate "$tmp/sim" --robots 3 --seed 3 > /dev/null
cd "$here"
[ -d node_modules ] || npm ci --no-audit --no-fund
rm -rf mcap_sim_seed3
node make_mcap.mjs --map "$tmp/sim/robot1.yaml" --out mcap_sim_seed3/robot1 --compression zstd --messages 3
node make_mcap.mjs --map "$tmp/sim/robot2.yaml" --out mcap_sim_seed3/robot2 --compression lz4 --messages 3
node make_mcap.mjs --map "$tmp/sim/robot3.yaml" --out mcap_sim_seed3/robot3 --compression none --messages 2
ls -l mcap_sim_seed3/*
