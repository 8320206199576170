#!/usr/bin/env bash
# The translation penalty of a pair with a fixed map (FleetOptions::fixed_map_free_penalty): per
# whole real building in ../shared and seed, `fleetmerge simulate` robots in the building, then
# `fleetmerge pair <building> <robot> --free-penalty P` for each robot and penalty. Counts, per
# building and penalty, the robots whose best hypothesis is within 1 deg and 3 cells of the truth
# (the pair alone: no fleet checks). Needs a build (scripts/build.sh) and ../shared/data/maps;
# about 1 minute per penalty on 2 cores.
# Usage: scripts/fixed_base_penalty.sh [OUT_DIR] [PENALTIES]   (default out/fixed_base_penalty,
# "2.0 0.5 0.25"); FIXED_BASE_SEEDS replaces the seed list (default 1 to 10), 5 robots each as
# scripts/fixed_base_accuracy.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/fixed_base_cases.sh fixed_base_penalty "${1:-out/fixed_base_penalty}"
penalties=${2:-2.0 0.5 0.25}
for building in $buildings; do
  for seed in $seeds; do
    dir=$out/${building}_$seed
    rm -rf "$dir"
    "$fleetmerge" simulate "$dir" --building "$maps/$building.yaml" --robots 5 --seed "$seed" \
      >/dev/null
    for penalty in $penalties; do
      for robot in "$dir"/robot*.yaml; do
        "$fleetmerge" pair "$maps/$building.yaml" "$robot" --free-penalty "$penalty" --json \
          >"${robot%.yaml}.pair_$penalty.json"
      done
    done
  done
done
/usr/bin/python3 - "$out" "$penalties" <<'PY'
import collections, glob, json, math, os, sys, yaml
out, penalties = sys.argv[1], sys.argv[2].split()
right = collections.defaultdict(int)
total = collections.defaultdict(int)
for truth_path in sorted(glob.glob(f"{out}/*/truth.yaml")):
    case = os.path.dirname(truth_path)
    building = os.path.basename(case).rsplit("_", 1)[0]
    for m in yaml.safe_load(open(truth_path))["maps"]:
        meta = yaml.safe_load(open(f"{case}/{m['file']}"))
        with open(f"{case}/{meta['image']}", "rb") as f:
            width, height = (int(v) for v in f.read(64).split()[1:3])
        res = meta["resolution"]
        # the centre of the robot's image, in its map frame
        cx = meta["origin"][0] + width * res / 2
        cy = meta["origin"][1] + height * res / 2
        for penalty in penalties:
            total[building, penalty] += 1
            pair = json.load(open(f"{case}/{m['name']}.pair_{penalty}.json"))
            if not pair["hypotheses"]:
                continue
            h = pair["hypotheses"][0]
            t = m["pose"]
            def at(x, y, yaw):
                c, s = math.cos(yaw), math.sin(yaw)
                return x + c * cx - s * cy, y + s * cx + c * cy
            (ex, ey), (tx, ty) = at(h["x"], h["y"], h["yaw"]), at(t["x"], t["y"], t["yaw"])
            yaw_deg = abs(math.degrees(math.remainder(h["yaw"] - t["yaw"], 2 * math.pi)))
            if yaw_deg <= 1.0 and math.hypot(ex - tx, ey - ty) / res <= 3.0:
                right[building, penalty] += 1
buildings = sorted({b for b, _ in total})
print("robots whose pair with the building's map is right (best hypothesis within 1 deg, 3 cells)")
print("building".ljust(22) + "".join(f"P={p}".rjust(10) for p in penalties))
for b in buildings:
    print(b.ljust(22) + "".join(f"{right[b, p]}/{total[b, p]}".rjust(10) for p in penalties))
print("all".ljust(22) + "".join(
    f"{sum(right[b, p] for b in buildings)}/{sum(total[b, p] for b in buildings)}".rjust(10)
    for p in penalties))
PY
