#!/usr/bin/env bash
# Fixed base maps on every real building in ../shared (issue 22's "robots simulated in a real
# building merged against that building's map as a fixed base: every robot within 1 deg and 3
# cells"): per building and seed, `fleetmerge simulate` robots in the building, then a job whose
# first map is the building's own map, fixed at a pose (seeds alternate the identity and
# (7.3 m, -12.1 m, 0.6 rad)), and the robots. Each robot's pose in the merged frame is compared
# with the truth (its pose in the building composed with the base's pose): the yaw error and the
# displacement of the centre of its map, in its cells.
# Each case also holds a robot of the next building in the list, which must be left out.
# The base's known cells must come out unchanged in the merged map: scripts/fixed_base_checks.py
# compares them with the merged map of a job of the base alone.
# Prints one line per case (robots, placed right, placed wrong, left out, worst yaw and
# displacement of the placed ones, whether the base kept its pose exactly, whether the other
# building's robot was placed: 0 or 1, the base's known cells changed) and the totals.
# Needs a build (scripts/build.sh) and ../shared/data/maps; about 3 minutes on 2 cores.
# Usage: scripts/fixed_base_accuracy.sh [OUT_DIR] [ROBOTS]   (default out/fixed_base, 5)
# FIXED_BASE_SEEDS replaces the seed list (default 1 to 10).
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/fixed_base_cases.sh fixed_base_accuracy "${1:-out/fixed_base}"
robots=${2:-5}

# Each case also holds a robot of the next building in the list (simulate --foreign), which must
# be left out.
read -r -a list <<<"$(echo $buildings)"
for index in "${!list[@]}"; do
  building=${list[$index]}
  foreign=${list[$(((index + 1) % ${#list[@]}))]}
  for seed in $seeds; do
    dir=$out/${building}_$seed
    rm -rf "$dir"
    "$fleetmerge" simulate "$dir" --building "$maps/$building.yaml" --robots "$robots" \
      --seed "$seed" --foreign "$maps/$foreign.yaml" >/dev/null
    /usr/bin/python3 - "$dir" "$(realpath "$maps/$building.yaml")" "$seed" <<'PY'
import sys, yaml
case, base, seed = sys.argv[1], sys.argv[2], int(sys.argv[3])
truth = yaml.safe_load(open(f"{case}/truth.yaml"))
pose = [7.3, -12.1, 0.6] if seed % 2 else [0.0, 0.0, 0.0]
job = {"name": "fixed_base",
       "maps": [{"path": base, "name": "base", "fixed": True, "pose": pose}] +
               [m["file"] for m in truth["maps"]],
       "output": "merged_fixed"}
yaml.safe_dump(job, open(f"{case}/job_fixed.yaml", "w"))
# The base alone: its merged map is its cells as fleetmerge reads them, where its pose puts them.
job.update(maps=job["maps"][:1], output="base_alone")
yaml.safe_dump(job, open(f"{case}/job_base_alone.yaml", "w"))
PY
    "$fleetmerge" merge --quiet "$dir/job_fixed.yaml" >/dev/null
    "$fleetmerge" merge --quiet "$dir/job_base_alone.yaml" >/dev/null
    /usr/bin/python3 - "$dir" "${building}_$seed" <<'PY'
import json, sys, yaml
sys.path.insert(0, "scripts")
from fixed_base_checks import base_cells_changed, centre_error, compose
case, name = sys.argv[1], sys.argv[2]
truth = yaml.safe_load(open(f"{case}/truth.yaml"))
report = json.load(open(f"{case}/merged_fixed/report.json"))
job = yaml.safe_load(open(f"{case}/job_fixed.yaml"))
placed = {m["name"]: m for m in report["maps"]}
base = placed["base"]
bx, by, byaw = job["maps"][0]["pose"]

right = wrong = left_out = foreign_placed = robots = 0
worst_yaw_deg = worst_cells = 0.0
for m in truth["maps"]:
    got = placed[m["name"]]
    if m["building"] != "building":  # the robot of another building
        foreign_placed += got["component"] == base["component"]
        continue
    robots += 1
    if got["component"] != base["component"]:
        left_out += 1
        continue
    t = compose((bx, by, byaw), (m["pose"]["x"], m["pose"]["y"], m["pose"]["yaw"]))
    e = (got["pose"]["x"], got["pose"]["y"], got["pose"]["yaw"])
    cells, yaw_deg = centre_error(e, t, f"{case}/{m['file']}")
    worst_yaw_deg, worst_cells = max(worst_yaw_deg, yaw_deg), max(worst_cells, cells)
    if yaw_deg <= 1.0 and cells <= 3.0:
        right += 1
    else:
        wrong += 1
exact = (base["pose"]["x"], base["pose"]["y"], base["pose"]["yaw"]) == (bx, by, byaw)

component = [c for c in report["components"] if "base" in c["maps"]][0]
cells_changed = base_cells_changed(f"{case}/base_alone/merged_0.yaml",
                                   f"{case}/merged_fixed/{component['merged_map']}")
print(name, robots, right, wrong, left_out, f"{worst_yaw_deg:.3f}", f"{worst_cells:.2f}",
      "base-exact" if exact else "BASE-MOVED", foreign_placed, cells_changed)
PY
  done
done | tee "$out/summary.txt"
awk '{n += $2; r += $3; w += $4; l += $5; moved += ($8 != "base-exact"); f += $9; changed += $10
      cases++}
     END {printf "fixed base: %d robots; within 1 deg and 3 cells %d (%.1f %%), placed wrong %d, left out %d; bases moved %d; base cells changed %d; robots of another building placed %d of %d\n",
          n, r, 100 * r / n, w, l, moved, changed, f, cases}' "$out/summary.txt"
