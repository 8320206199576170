#!/usr/bin/env bash
# A site map of 4000 x 4000 cells against robots that saw a few per cent of it (issue 22: "a
# 4000 x 4000-cell site against a robot that saw 5 % of it: the pair search must find a small map
# inside a large one, and not slowly"). No real map in ../shared is that large, so the site is a
# campus of four of them, 5 cm each, laid out on a 200 x 200 m map with unknown space between:
# GDC floors 1 and 2, MIT CSAIL and ACES (1.6 M known cells of 16 M). Per seed, ROBOTS robots
# are simulated in the site (`fleetmerge simulate --building`, PATH_M m paths; they start at random
# free places, so in any of the buildings), then:
#   pair:  `fleetmerge pair SITE ROBOT --free-penalty 0.25` for each robot (the penalty merge
#          uses for a pair with a fixed map): right when its best hypothesis is within 1 deg and
#          3 cells of the truth (at the robot map's centre); its wall time and peak memory. Also
#          `fleetmerge pair ROBOT SITE` (a job that lists the site after the robots), right the
#          same way once inverted;
#   merge: the job of the site, fixed at the identity, and the robots: each robot right, wrong or
#          left out; the job's wall time and peak memory;
#   daily: the same job with a cache that the seeds share, as a site's daily jobs do (`cache:`;
#          every seed's robots are new, the site is not): from the second seed on, the site's
#          preparation comes from the cache; its wall time, and a check that it places every map
#          as the job without a cache did. Each job runs 3 times, alternating with the other,
#          each daily run with the cache as the seeds before left it.
# Prints one line per seed (robots; site pairs right, and with the site second; robots placed
# right, wrong, left out; the worst placed robot's cells; each site pair's seconds; their peak MB;
# the daily job's seconds; the job's seconds and peak MB), then the totals with the median times.
# Needs a build (scripts/build.sh, or BUILD_DIR), ../shared/data/maps and /usr/bin/time (Debian
# package time); about 20 s per seed.
# Usage: scripts/large_site_benchmark.sh [OUT_DIR] [ROBOTS] [SEEDS] [PATH_M]
#   (default out/large_site, 3, "1 2 3 4 5 6 7 8 9 10", 100: each robot's path in metres)
set -euo pipefail
cd "$(dirname "$0")/.."
fleetmerge=${BUILD_DIR:-build}/cli/fleetmerge
maps=../shared/data/maps
out=${1:-out/large_site}
robots=${2:-3}
seeds=${3:-1 2 3 4 5 6 7 8 9 10}
path_m=${4:-100}
if [ ! -d "$maps" ]; then
  echo "large_site_benchmark: $maps is missing (the real building maps)" >&2
  exit 1
fi
if [ ! -x /usr/bin/time ]; then  # wall time and peak memory of each process
  echo "large_site_benchmark: /usr/bin/time is missing (Debian package 'time')" >&2
  exit 1
fi
rm -rf "$out"
mkdir -p "$out"

/usr/bin/python3 - "$maps" "$out" <<'PY'
import os, sys
import numpy as np
import yaml

maps, out = sys.argv[1], sys.argv[2]
side = 4000
# Building, first column and first row of its image in the site's image (row 0 at the top).
campus = [("gdc_floor1_full", 100, 100), ("gdc_floor2_full", 2100, 100),
          ("mit_csail", 100, 2150), ("aces3_austin", 2300, 2300)]

def read_pgm(path):  # binary PGM, 8 bits
    data = open(path, "rb").read()
    fields, pos = [], 0
    while len(fields) < 4:
        while data[pos:pos + 1].isspace():
            pos += 1
        if data[pos:pos + 1] == b"#":
            pos = data.index(b"\n", pos) + 1
            continue
        end = pos
        while not data[end:end + 1].isspace():
            end += 1
        fields.append(data[pos:end])
        pos = end
    width, height, maxval = int(fields[1]), int(fields[2]), int(fields[3])
    if fields[0] != b"P5" or maxval > 255:
        sys.exit(f"large_site_benchmark: {path}: not an 8-bit binary PGM")
    return np.frombuffer(data, np.uint8, width * height, pos + 1).reshape(height, width)

site = np.full((side, side), 205, np.uint8)  # unknown
for name, col, row in campus:
    meta = yaml.safe_load(open(os.path.join(maps, name + ".yaml")))
    if abs(meta["resolution"] - 0.05) > 1e-9:
        sys.exit(f"large_site_benchmark: {name}: resolution {meta['resolution']}, expected 0.05")
    pixels = read_pgm(os.path.join(maps, meta["image"])).astype(np.float64)
    # map_server's trinary reading of the building's own thresholds.
    p = pixels / 255.0 if meta.get("negate", 0) else (255.0 - pixels) / 255.0
    cells = np.full(pixels.shape, 205, np.uint8)
    cells[p > meta["occupied_thresh"]] = 0
    cells[p < meta["free_thresh"]] = 254
    site[row:row + cells.shape[0], col:col + cells.shape[1]] = cells
with open(os.path.join(out, "site.pgm"), "wb") as f:
    f.write(b"P5\n%d %d\n255\n" % (side, side) + site.tobytes())
yaml.safe_dump({"image": "site.pgm", "resolution": 0.05, "origin": [0.0, 0.0, 0.0],
                "negate": 0, "occupied_thresh": 0.65, "free_thresh": 0.196},
               open(os.path.join(out, "site.yaml"), "w"), default_flow_style=None)
PY

site=$(realpath "$out/site.yaml")
for seed in $seeds; do
  case_dir=$out/seed$seed
  "$fleetmerge" simulate "$case_dir" --building "$site" --robots "$robots" --seed "$seed" \
    --path-length "$path_m" >/dev/null
  for ((k = 1; k <= robots; k++)); do
    /usr/bin/time -f "%e %M" -o "$case_dir/pair$k.time" "$fleetmerge" pair "$site" \
      "$case_dir/robot$k.yaml" --free-penalty 0.25 -n 1 --json >"$case_dir/pair$k.json"
    "$fleetmerge" pair "$case_dir/robot$k.yaml" "$site" --free-penalty 0.25 -n 1 --json \
      >"$case_dir/pair${k}_reversed.json"
  done
  /usr/bin/python3 - "$case_dir" "$site" <<'PY'
import sys, yaml
case, site = sys.argv[1], sys.argv[2]
truth = yaml.safe_load(open(f"{case}/truth.yaml"))
job = {"name": "site", "maps": [{"path": site, "name": "site", "fixed": True}] +
       [m["file"] for m in truth["maps"]], "output": "merged_site"}
yaml.safe_dump(job, open(f"{case}/job_site.yaml", "w"))
job.update(output="merged_site_daily", cache="../daily_cache")
yaml.safe_dump(job, open(f"{case}/job_site_daily.yaml", "w"))
PY
  # Three of each, alternating (the machine's speed drifts); medians. Each daily run starts from
  # the cache as the seeds before left it.
  rm -rf "$out/daily_cache.before"
  if [ -d "$out/daily_cache" ]; then cp -r "$out/daily_cache" "$out/daily_cache.before"; fi
  for ((k = 1; k <= 3; k++)); do
    /usr/bin/time -f "%e %M" -o "$case_dir/merge$k.time" "$fleetmerge" merge --quiet --force \
      "$case_dir/job_site.yaml" >/dev/null
    rm -rf "$out/daily_cache"
    if [ -d "$out/daily_cache.before" ]; then cp -r "$out/daily_cache.before" "$out/daily_cache"; fi
    /usr/bin/time -f "%e %M" -o "$case_dir/daily$k.time" "$fleetmerge" merge --quiet --force \
      "$case_dir/job_site_daily.yaml" >/dev/null
  done
  /usr/bin/python3 - "$case_dir" "$seed" <<'PY'
import json, math, sys
import yaml

case, seed = sys.argv[1], sys.argv[2]
truth = yaml.safe_load(open(f"{case}/truth.yaml"))

def compose(a, b):  # (x, y, yaw) poses: a * b
    c, s = math.cos(a[2]), math.sin(a[2])
    return (a[0] + c * b[0] - s * b[1], a[1] + s * b[0] + c * b[1], a[2] + b[2])

def inverse(a):
    c, s = math.cos(a[2]), math.sin(a[2])
    return (-(c * a[0] + s * a[1]), s * a[0] - c * a[1], -a[2])

def best(name):  # the best hypothesis of a `fleetmerge pair --json`
    h = json.load(open(f"{case}/{name}.json"))["hypotheses"][0]
    return (h["x"], h["y"], h["yaw"])

def error(got, true, file):  # yaw error (deg) and displacement of the map's centre (cells)
    meta = yaml.safe_load(open(f"{case}/{file}"))
    with open(f"{case}/{meta['image']}", "rb") as f:
        width, height = (int(v) for v in f.read(64).split()[1:3])
    r = meta["resolution"]
    centre = (meta["origin"][0] + width * r / 2, meta["origin"][1] + height * r / 2, 0.0)
    pg, pt = compose(got, centre), compose(true, centre)
    yaw = math.degrees(math.atan2(math.sin(got[2] - true[2]), math.cos(got[2] - true[2])))
    return abs(yaw), math.hypot(pg[0] - pt[0], pg[1] - pt[1]) / r

def time_of(name):
    seconds, kb = open(f"{case}/{name}.time").read().split()[-2:]
    return float(seconds), int(kb) / 1024

pair_right, reversed_right, pair_times, pair_mb = 0, 0, [], []
for k, m in enumerate(truth["maps"], 1):
    true = (m["pose"]["x"], m["pose"]["y"], m["pose"]["yaw"])
    yaw, cells = error(best(f"pair{k}"), true, m["file"])
    pair_right += yaw <= 1.0 and cells <= 3.0
    yaw, cells = error(inverse(best(f"pair{k}_reversed")), true, m["file"])
    reversed_right += yaw <= 1.0 and cells <= 3.0
    seconds, mb = time_of(f"pair{k}")
    pair_times.append(seconds)
    pair_mb.append(mb)
report = json.load(open(f"{case}/merged_site/report.json"))
placed = {m["name"]: m for m in report["maps"]}
right = wrong = left_out = 0
worst = 0.0
for m in truth["maps"]:
    got = placed[m["name"]]
    if got["component"] != placed["site"]["component"]:
        left_out += 1
        continue
    true = (m["pose"]["x"], m["pose"]["y"], m["pose"]["yaw"])
    yaw, cells = error((got["pose"]["x"], got["pose"]["y"], got["pose"]["yaw"]), true, m["file"])
    worst = max(worst, cells)
    if yaw <= 1.0 and cells <= 3.0:
        right += 1
    else:
        wrong += 1
daily = json.load(open(f"{case}/merged_site_daily/report.json"))
if [m["pose"] for m in daily["maps"]] != [m["pose"] for m in report["maps"]]:
    sys.exit(f"seed {seed}: the job with the daily cache placed the maps otherwise")
merges = [time_of(f"merge{k}") for k in (1, 2, 3)]
seconds, mb = sorted(s for s, _ in merges)[1], max(m for _, m in merges)
daily_seconds = sorted(time_of(f"daily{k}")[0] for k in (1, 2, 3))[1]
print(f"seed{seed} {len(truth['maps'])} {pair_right} {reversed_right} {right} {wrong} {left_out} "
      f"{worst:.2f} "
      + " ".join(f"{t:.2f}" for t in pair_times)
      + f" {max(pair_mb):.0f} {daily_seconds:.2f} {seconds:.2f} {mb:.0f}")
PY
done | tee "$out/summary.txt"
/usr/bin/python3 - "$out/summary.txt" "$robots" <<'PY'
import statistics, sys
rows = [line.split() for line in open(sys.argv[1])]
robots = int(sys.argv[2])
n = sum(int(r[1]) for r in rows)
pair_times = [float(t) for r in rows for t in r[8:8 + robots]]
print(f"large site (4000 x 4000 cells), {len(rows)} seeds, {n} robots: pairs with the site right "
      f"{sum(int(r[2]) for r in rows)} (site second: {sum(int(r[3]) for r in rows)}), median "
      f"{statistics.median(pair_times):.2f} s, peak {max(float(r[8 + robots]) for r in rows):.0f} "
      f"MB; merged with the site fixed: right {sum(int(r[4]) for r in rows)}, wrong "
      f"{sum(int(r[5]) for r in rows)}, left out {sum(int(r[6]) for r in rows)}, worst "
      f"{max(float(r[7]) for r in rows):.2f} cells; job median "
      f"{statistics.median(float(r[-2]) for r in rows):.2f} s, peak "
      f"{max(float(r[-1]) for r in rows):.0f} MB")
if len(rows) >= 2:  # the first seed fills the daily cache
    print(f"daily jobs with the cache of the seeds before (the site's preparation kept), "
          f"{len(rows) - 1} seeds: job median {statistics.median(float(r[-3]) for r in rows[1:]):.2f}"
          f" s, the same seeds without a cache {statistics.median(float(r[-2]) for r in rows[1:]):.2f}"
          f" s")
PY
