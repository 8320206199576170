#!/usr/bin/env bash
# A site's daily jobs, day after day: day 1's base is a real building's map; each later day's
# base is the day before's merged map (report.json's components[].merged_map), fixed at the
# identity, as configs/README.md ("Fixed (base) maps") tells a site to run. Each day ROBOTS new
# robots are simulated in the building (`fleetmerge simulate --building`, seed 100 + day) and
# merged with that base, all days sharing one cache. Per day it prints:
#   - the worst robot against the truth (cells at its map's centre, degrees), and robots not
#     placed by pairs;
#   - the base's known cells that the merged map changed (it must keep them: 0), against a job
#     of the base alone (scripts/fixed_base_checks.py), and the merged map's occupied and free
#     cells, which show a wall growing day by day;
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
import json, os, subprocess, sys, time
import yaml
sys.path.insert(0, "scripts")
from fixed_base_checks import FREE, OCCUPIED, base_cells_changed, centre_error, load_merged

fleetmerge, building, out, days, robots = sys.argv[1:4] + [int(a) for a in sys.argv[4:6]]

def merge(name, maps, cache=None):
    """Runs a job of these map entries; returns its output folder, report and wall time."""
    job = {"name": name, "output": os.path.abspath(os.path.join(out, name)), "maps": maps}
    if cache:
        job["cache"] = os.path.abspath(cache)
    job_file = os.path.join(out, name + ".yaml")
    with open(job_file, "w") as f:
        yaml.safe_dump(job, f)
    start = time.monotonic()
    run = subprocess.run([fleetmerge, "merge", "--quiet", job_file], capture_output=True, text=True)
    seconds = time.monotonic() - start
    if run.returncode != 0:
        sys.exit(run.stdout + run.stderr)
    return job["output"], json.load(open(os.path.join(job["output"], "report.json"))), seconds

def cell_counts(yaml_path):
    cells = load_merged(yaml_path)[1]
    return f"occupied {int((cells == OCCUPIED).sum())}, free {int((cells == FREE).sum())}"

base = os.path.abspath(building)
for day in range(1, days + 1):
    # The base as fleetmerge reads it (trinary cells, where its pose puts them): what the merged
    # map must keep.
    site = {"path": base, "name": "site", "fixed": True}
    alone = os.path.join(merge(f"site_alone{day}", [site])[0], "merged_0.yaml")
    if day == 1:
        print(f"day 0: {os.path.basename(base)}: {cell_counts(alone)}")
    case = os.path.join(out, f"day{day}")
    subprocess.run([fleetmerge, "simulate", case, "--building", building, "--robots", str(robots),
                    "--seed", str(100 + day)], check=True, capture_output=True)
    truth = yaml.safe_load(open(os.path.join(case, "truth.yaml")))
    output, report, seconds = merge(
        f"merged{day}", [site] + [os.path.abspath(os.path.join(case, m["file"]))
                                  for m in truth["maps"]], os.path.join(out, "cache"))
    by_name = {m["name"]: m for m in report["maps"]}
    merged = [c for c in report["components"] if "site" in c["maps"]][0]["merged_map"]
    merged = os.path.join(output, merged)
    worst_cells = worst_deg = 0.0
    not_by_pairs = []
    for m in truth["maps"]:
        p, t = by_name[m["name"]]["pose"], m["pose"]
        e_cells, e_deg = centre_error((p["x"], p["y"], p["yaw"]), (t["x"], t["y"], t["yaw"]),
                                      os.path.join(case, m["file"]))
        worst_cells, worst_deg = max(worst_cells, e_cells), max(worst_deg, e_deg)
        if by_name[m["name"]]["placed_by"] != "pairs":
            not_by_pairs.append(m["name"])
    cache = report["cache"]
    print(f"day {day}: worst robot {worst_cells:.2f} cells, {worst_deg:.3f} deg; "
          f"not placed by pairs: {not_by_pairs or 'none'}; "
          f"base cells changed {base_cells_changed(alone, merged)}; "
          f"merged {cell_counts(merged)}; "
          f"{seconds:.2f} s, pairs cached {cache['pairs_cached']}, "
          f"computed {cache['pairs_computed']}", flush=True)
    base = os.path.abspath(merged)
PY
