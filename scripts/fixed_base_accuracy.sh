#!/usr/bin/env bash
# Fixed base maps on every real building in ../shared (issue 22's "robots simulated in a real
# building merged against that building's map as a fixed base: every robot within 1 deg and 3
# cells"): per building and seed, `fleetmerge simulate` robots in the building, then a job whose
# first map is the building's own map, fixed at a pose (seeds alternate the identity and
# (7.3 m, -12.1 m, 0.6 rad)), and the robots. Each robot's pose in the merged frame is compared
# with the truth (its pose in the building composed with the base's pose): the yaw error and the
# displacement of the centre of its map, in its cells.
# Each case also holds a robot of the next building in the list, which must be left out.
# The base's known cells must come out unchanged in the merged map: they are compared with the
# merged map of a job of the base alone (fleetmerge writes a fixed map alone as it reads it, on
# its lattice moved by its pose).
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
import json, math, os, sys, yaml
import numpy as np
case, name = sys.argv[1], sys.argv[2]
truth = yaml.safe_load(open(f"{case}/truth.yaml"))
report = json.load(open(f"{case}/merged_fixed/report.json"))
job = yaml.safe_load(open(f"{case}/job_fixed.yaml"))
placed = {m["name"]: m for m in report["maps"]}
base = placed["base"]
bx, by, byaw = job["maps"][0]["pose"]

def compose(a, b):  # (x, y, yaw) poses: a * b
    c, s = math.cos(a[2]), math.sin(a[2])
    return (a[0] + c * b[0] - s * b[1], a[1] + s * b[0] + c * b[1], a[2] + b[2])

def wrap(angle):
    return math.atan2(math.sin(angle), math.cos(angle))

def map_centre(yaml_path):  # the centre of the map's image, in its map frame
    meta = yaml.safe_load(open(f"{case}/{yaml_path}"))
    with open(f"{case}/{meta['image']}", "rb") as f:
        width, height = (int(v) for v in f.read(64).split()[1:3])
    ox, oy = meta["origin"][0], meta["origin"][1]
    return (ox + width * meta["resolution"] / 2, oy + height * meta["resolution"] / 2), meta["resolution"]

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
    (cx, cy), resolution = map_centre(m["file"])
    pt, pe = compose(t, (cx, cy, 0)), compose(e, (cx, cy, 0))
    yaw_deg = abs(math.degrees(wrap(e[2] - t[2])))
    cells = math.hypot(pt[0] - pe[0], pt[1] - pe[1]) / resolution
    worst_yaw_deg, worst_cells = max(worst_yaw_deg, yaw_deg), max(worst_cells, cells)
    if yaw_deg <= 1.0 and cells <= 3.0:
        right += 1
    else:
        wrong += 1
exact = (base["pose"]["x"], base["pose"]["y"], base["pose"]["yaw"]) == (bx, by, byaw)

def load_merged(yaml_path):  # a merged map: its YAML and cells (trinary PGM, row 0 at the top)
    meta = yaml.safe_load(open(yaml_path))
    data = open(os.path.join(os.path.dirname(yaml_path), meta["image"]), "rb").read()
    width, height = (int(v) for v in data.split(maxsplit=3)[1:3])  # P5 W H 255: no comments
    return meta, np.frombuffer(data[len(data) - width * height:], np.uint8).reshape(height, width)

def cells_changed():
    # The base's known cells (from its merged map alone) against the job's merged map: both
    # lattices are the base's moved by its pose, so one whole-cell offset maps one onto the other.
    component = [c for c in report["components"] if "base" in c["maps"]][0]
    alone_meta, alone = load_merged(f"{case}/base_alone/merged_0.yaml")
    meta, merged = load_merged(f"{case}/merged_fixed/{component['merged_map']}")
    r, yaw = meta["resolution"], meta["origin"][2]
    if alone_meta["resolution"] != r or abs(alone_meta["origin"][2] - yaw) > 1e-12:
        return int((alone != 205).sum())
    d = np.array(alone_meta["origin"][:2]) - np.array(meta["origin"][:2])
    c, s = math.cos(yaw), math.sin(yaw)
    offset = np.array([c * d[0] + s * d[1], -s * d[0] + c * d[1]]) / r  # in merged cells
    if np.abs(offset - np.round(offset)).max() > 1e-6:
        return int((alone != 205).sum())
    dx, dy = (int(v) for v in np.round(offset))
    rows, cols = np.nonzero(alone != 205)
    merged_rows = merged.shape[0] - 1 - (alone.shape[0] - 1 - rows + dy)
    merged_cols = cols + dx
    inside = ((merged_rows >= 0) & (merged_rows < merged.shape[0]) & (merged_cols >= 0) &
              (merged_cols < merged.shape[1]))
    same = merged[merged_rows[inside], merged_cols[inside]] == alone[rows[inside], cols[inside]]
    return int((~inside).sum() + (~same).sum())

print(name, robots, right, wrong, left_out, f"{worst_yaw_deg:.3f}", f"{worst_cells:.2f}",
      "base-exact" if exact else "BASE-MOVED", foreign_placed, cells_changed())
PY
  done
done | tee "$out/summary.txt"
awk '{n += $2; r += $3; w += $4; l += $5; moved += ($8 != "base-exact"); f += $9; changed += $10
      cases++}
     END {printf "fixed base: %d robots; within 1 deg and 3 cells %d (%.1f %%), placed wrong %d, left out %d; bases moved %d; base cells changed %d; robots of another building placed %d of %d\n",
          n, r, 100 * r / n, w, l, moved, changed, f, cases}' "$out/summary.txt"
