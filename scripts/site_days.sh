#!/usr/bin/env bash
# A site's daily jobs, day after day: day 1's base is a real building's map; each later day's
# base is the day before's merged map (report.json's components[].merged_map), fixed at the
# identity, as configs/README.md ("Fixed (base) maps") tells a site to run. Each day ROBOTS new
# robots are simulated in the building (`fleetmerge simulate --building`, seed 100 + day) and
# merged with that base, all days sharing one cache. Per day it prints:
#   - the worst robot against the truth (cells at its map's centre, degrees), and robots not
#     placed by pairs;
#   - the base's known cells that the merged map changed (the merged map must keep them: 0),
#     and the merged map's occupied and free cells, which show a wall growing day by day;
#   - the job's wall time and the pairs it took from the cache / computed.
# Needs a build (scripts/build.sh, or BUILD_DIR) and ../shared/data/maps.
# Usage: scripts/site_days.sh [OUT_DIR] [DAYS] [ROBOTS] [BUILDING]
#   (default out/site_days, 5, 3, intel_lab: a map YAML name in ../shared/data/maps)
set -euo pipefail
cd "$(dirname "$0")/.."
fleetmerge=${BUILD_DIR:-build}/cli/fleetmerge
maps=../shared/data/maps
out=${1:-out/site_days}
days=${2:-5}
robots=${3:-3}
building=${4:-intel_lab}
if [ ! -f "$maps/$building.yaml" ]; then
  echo "site_days: $maps/$building.yaml is missing (the real building maps)" >&2
  exit 1
fi
rm -rf "$out"
mkdir -p "$out"
/usr/bin/python3 - "$fleetmerge" "$maps/$building.yaml" "$out" "$days" "$robots" <<'PY'
import json, math, os, subprocess, sys, time
import numpy as np
import yaml

fleetmerge, building, out, days, robots = sys.argv[1:4] + [int(a) for a in sys.argv[4:6]]
UNKNOWN, OCCUPIED, FREE = 205, 0, 254  # trinary PGM values of the maps fleetmerge writes

def load(yaml_path):
    """A map: its YAML and its PGM's cells (row 0 at the top), as map_server reads them."""
    meta = yaml.safe_load(open(yaml_path))
    data = open(os.path.join(os.path.dirname(yaml_path), meta["image"]), "rb").read()
    fields, pos = [], 0
    while len(fields) < 4:  # P5, width, height, maxval; comments allowed between them
        while data[pos:pos + 1].isspace():
            pos += 1
        if data[pos:pos + 1] == b"#":
            pos = data.index(b"\n", pos)
            continue
        start = pos
        while not data[pos:pos + 1].isspace():
            pos += 1
        fields.append(data[start:pos])
    if fields[0] != b"P5" or fields[3] != b"255":
        sys.exit(f"site_days: {yaml_path}: not an 8-bit binary PGM")
    width, height = int(fields[1]), int(fields[2])
    return meta, np.frombuffer(data, np.uint8, width * height, pos + 1).reshape(height, width)

def changed_cells(base_yaml, merged_yaml):
    """The base's known cells that the merged map does not hold as they are (same lattice)."""
    base_meta, base = load(base_yaml)
    merged_meta, merged = load(merged_yaml)
    r = merged_meta["resolution"]
    offset = (np.array(base_meta["origin"][:2]) - np.array(merged_meta["origin"][:2])) / r
    if np.abs(offset - np.round(offset)).max() > 1e-6 or base_meta["resolution"] != r:
        return int((base != UNKNOWN).sum())  # another lattice: nothing is kept cell for cell
    dx, dy = (int(v) for v in np.round(offset))
    rows, cols = np.nonzero(base != UNKNOWN)
    merged_rows = merged.shape[0] - 1 - ((base.shape[0] - 1 - rows) + dy)  # rows from the top
    merged_cols = cols + dx
    inside = ((merged_rows >= 0) & (merged_rows < merged.shape[0]) & (merged_cols >= 0) &
              (merged_cols < merged.shape[1]))
    same = merged[merged_rows[inside], merged_cols[inside]] == base[rows[inside], cols[inside]]
    return int((~inside).sum() + (~same).sum())

def centre_error(report_map, truth_map, map_yaml):
    """Cells and degrees between the reported and true poses, at the map's centre."""
    meta, cells = load(map_yaml)
    r = meta["resolution"]
    c = np.array(meta["origin"][:2]) + 0.5 * r * np.array([cells.shape[1], cells.shape[0]])
    def at(x, y, yaw):
        return np.array([x + math.cos(yaw) * c[0] - math.sin(yaw) * c[1],
                         y + math.sin(yaw) * c[0] + math.cos(yaw) * c[1]])
    p, t = report_map["pose"], truth_map["pose"]
    cells_off = np.linalg.norm(at(p["x"], p["y"], p["yaw"]) - at(t["x"], t["y"], t["yaw"])) / r
    yaw_deg = abs(math.degrees((p["yaw"] - t["yaw"] + math.pi) % (2 * math.pi) - math.pi))
    return cells_off, yaw_deg

base = os.path.abspath(building)
meta, cells = load(base)
print(f"day 0: {os.path.basename(base)}: occupied {int((cells == OCCUPIED).sum())}, "
      f"free {int((cells == FREE).sum())}")
for day in range(1, days + 1):
    case = os.path.join(out, f"day{day}")
    subprocess.run([fleetmerge, "simulate", case, "--building", building, "--robots", str(robots),
                    "--seed", str(100 + day)], check=True, capture_output=True)
    truth = yaml.safe_load(open(os.path.join(case, "truth.yaml")))
    job = {"name": f"day{day}", "output": os.path.abspath(os.path.join(out, f"merged{day}")),
           "cache": os.path.abspath(os.path.join(out, "cache")),
           "maps": [{"path": base, "name": "site", "fixed": True}] +
                   [os.path.abspath(os.path.join(case, m["file"])) for m in truth["maps"]]}
    job_file = os.path.join(out, f"day{day}.yaml")
    with open(job_file, "w") as f:
        yaml.safe_dump(job, f)
    start = time.monotonic()
    run = subprocess.run([fleetmerge, "merge", "--quiet", job_file], capture_output=True, text=True)
    seconds = time.monotonic() - start
    if run.returncode != 0:
        sys.exit(run.stdout + run.stderr)
    report = json.load(open(os.path.join(job["output"], "report.json")))
    by_name = {m["name"]: m for m in report["maps"]}
    merged = [c for c in report["components"] if "site" in c["maps"]][0]["merged_map"]
    merged = os.path.join(job["output"], merged)
    worst_cells = worst_deg = 0.0
    not_by_pairs = []
    for m in truth["maps"]:
        e_cells, e_deg = centre_error(by_name[m["name"]], m, os.path.join(case, m["file"]))
        worst_cells, worst_deg = max(worst_cells, e_cells), max(worst_deg, e_deg)
        if by_name[m["name"]]["placed_by"] != "pairs":
            not_by_pairs.append(m["name"])
    meta, cells = load(merged)
    cache = report["cache"]
    print(f"day {day}: worst robot {worst_cells:.2f} cells, {worst_deg:.3f} deg; "
          f"not placed by pairs: {not_by_pairs or 'none'}; "
          f"base cells changed {changed_cells(base, merged)}; "
          f"merged occupied {int((cells == OCCUPIED).sum())}, free {int((cells == FREE).sum())}; "
          f"{seconds:.2f} s, pairs cached {cache['pairs_cached']}, "
          f"computed {cache['pairs_computed']}", flush=True)
    base = os.path.abspath(merged)
PY
