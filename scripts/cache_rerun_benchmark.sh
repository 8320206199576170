#!/usr/bin/env bash
# Re-runs that reuse earlier work (fleetmerge merge --cache): N robots (default 33) simulated in
# the ACES building (aces3_austin in ../shared, seed 7, simulate's default paths). Per repetition:
#   cold:  the N-robot job without a cache;
#   prime: the job of the first N - 1 robots with an empty cache (not timed);
#   warm:  the N-robot job with that cache (N - 1 new pairs computed, the others from the cache);
#   again: the N-robot job once more (no map new: every pair from the cache), what any re-run
#          pays besides its new pairs.
# Prints each repetition's three wall times and the medians' ratios to the cold run's (the issue
# asks for warm at most 10 %), checks that both cached runs' report.json have the cold run's
# poses, pairs and hypotheses exactly, and prints the three runs' stage times (report.json's
# timing_ms). Last, the warm run split into its pair stage and the rest, and its CPU time per
# core: the least wall time it could take with every core busy.
# NEW picks which robot is the new one (1..N, default N): the job lists the others in their
# order, then robot NEW, and its first N - 1 maps are the cached run's. A new robot's pairs cost
# what its map's size makes them cost (docs/speed.md, "Re-runs", has each robot as the new one).
# Needs a build (scripts/build.sh, or BUILD_DIR) and ../shared/data/maps.
# Usage: scripts/cache_rerun_benchmark.sh [OUT_DIR] [REPETITIONS] [ROBOTS] [NEW]
#   (default out/cache_rerun, 3, 33, ROBOTS; 100 robots take about 90 s per repetition)
set -euo pipefail
cd "$(dirname "$0")/.."
fleetmerge=${BUILD_DIR:-build}/cli/fleetmerge
maps=../shared/data/maps
out=${1:-out/cache_rerun}
repetitions=${2:-3}
robots=${3:-33}
new=${4:-$robots}
if ! [[ "$robots" =~ ^[0-9]+$ ]] || [ "$robots" -lt 3 ]; then
  echo "cache_rerun_benchmark: ROBOTS must be a whole number >= 3, got '$robots'" >&2
  exit 1
fi
if ! [[ "$new" =~ ^[0-9]+$ ]] || [ "$new" -lt 1 ] || [ "$new" -gt "$robots" ]; then
  echo "cache_rerun_benchmark: NEW must be a whole number in [1, $robots], got '$new'" >&2
  exit 1
fi
if [ ! -d "$maps" ]; then
  echo "cache_rerun_benchmark: $maps is missing (the real building maps)" >&2
  exit 1
fi
rm -rf "$out"
mkdir -p "$out"
"$fleetmerge" simulate "$out/case" --building "$maps/aces3_austin.yaml" --robots "$robots" --seed 7 \
  >/dev/null
/usr/bin/python3 - "$fleetmerge" "$out" "$repetitions" "$robots" "$new" <<'PY'
import json, os, resource, shutil, statistics, subprocess, sys, time
import yaml

fleetmerge, out, repetitions, robots = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4])
new = int(sys.argv[5])  # 1-based
case = os.path.join(out, "case")
job = yaml.safe_load(open(os.path.join(case, "job.yaml")))
maps = [m if isinstance(m, str) else m["path"] for m in job["maps"]]
maps = [os.path.join(os.path.abspath(case), m) for m in maps]
assert len(maps) == robots, len(maps)
maps = maps[:new - 1] + maps[new:] + [maps[new - 1]]  # robot NEW last: the one the cache lacks

def cells(map_yaml):  # width x height of a map's PGM image
    image = yaml.safe_load(open(map_yaml))["image"]
    with open(os.path.join(os.path.dirname(map_yaml), image), "rb") as f:
        fields = f.read(64).split()  # P5 width height maxval: simulate writes no comments
    return f"{int(fields[1])} x {int(fields[2])} cells"

new_map = f"robot {new} ({cells(maps[-1])})"

def write_job(name, count):
    path = os.path.join(out, name + ".yaml")
    with open(path, "w") as f:
        yaml.safe_dump({"name": name, "maps": maps[:count], "output": name + "_out"}, f)
    return path

job_less = write_job(f"robots{robots - 1}", robots - 1)
job_all = write_job(f"robots{robots}", robots)
out_all = os.path.join(out, f"robots{robots}_out")
cache = os.path.join(out, "cache")

def merge(job_file, cache_dir=None):
    global last_cpu_s  # the run's CPU time (user + system), s
    args = [fleetmerge, "merge", "--quiet", "--force", job_file]
    if cache_dir:
        args += ["--cache", cache_dir]
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.monotonic()
    run = subprocess.run(args, capture_output=True, text=True)
    seconds = time.monotonic() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    last_cpu_s = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    if run.returncode != 0:
        sys.exit(run.stdout + run.stderr)
    return seconds, run.stdout

def comparable(report_path):
    report = json.load(open(report_path))
    return {k: report[k] for k in ("maps", "components", "pairs")}

cold, warm, again = [], [], []
warm_pairs_share, warm_rest_share = [], []  # of the same repetition's cold run
warm_cpu_share = []  # the warm run's CPU time over all cores, per core, of the cold run's wall
for rep in range(repetitions):
    shutil.rmtree(cache, ignore_errors=True)
    seconds, _ = merge(job_all)
    cold.append(seconds)
    cold_report = comparable(os.path.join(out_all, "report.json"))
    cold_timing = json.load(open(os.path.join(out_all, "report.json")))["timing_ms"]
    merge(job_less, cache)
    seconds, stdout = merge(job_all, cache)
    warm.append(seconds)
    warm_cpu_share.append(last_cpu_s / os.cpu_count() / cold[-1])
    report = json.load(open(os.path.join(out_all, "report.json")))
    same = comparable(os.path.join(out_all, "report.json")) == cold_report
    warm_timing = report["timing_ms"]
    warm_pairs_share.append(warm_timing["pairs"] / (1000 * cold[-1]))
    warm_rest_share.append((1000 * warm[-1] - warm_timing["pairs"]) / (1000 * cold[-1]))
    seconds, again_stdout = merge(job_all, cache)
    again.append(seconds)
    again_report = json.load(open(os.path.join(out_all, "report.json")))
    same = same and comparable(os.path.join(out_all, "report.json")) == cold_report
    print(f"repetition {rep + 1}: cold {cold[-1]:.2f} s, warm {warm[-1]:.2f} s, "
          f"again {again[-1]:.2f} s; {stdout.strip().splitlines()[-1]}; again: "
          f"{again_stdout.strip().splitlines()[-1].split(': ', 1)[1]}; "
          f"identical poses, pairs and hypotheses: {same}")
    if not same:
        sys.exit("a cached run differs from the cold run")
    if again_report["cache"]["pairs_computed"] != 0:
        sys.exit("the run with no new map computed pairs")
    for name, timing in (("cold", cold_timing), ("warm", warm_timing),
                         ("again", again_report["timing_ms"])):
        print(f"  {name} stages (ms): " + ", ".join(f"{k} {v:.0f}" for k, v in timing.items()))

cold_s, warm_s = statistics.median(cold), statistics.median(warm)
again_s = statistics.median(again)
print(f"median of {repetitions}: cold {robots} robots {cold_s:.2f} s, "
      f"warm with {new_map} new {warm_s:.2f} s, ratio {100 * warm_s / cold_s:.1f} %; "
      f"again with no map new {again_s:.2f} s, ratio {100 * again_s / cold_s:.1f} %")
# The warm run split in two: its pair stage (the new pairs, and the kept preparations of the maps
# they share with the new one read back), which grows as N with the fleet where the cold run's
# grows as N^2 / 2; and the rest of the process (loading, refine, composite, outputs, start-up),
# which every run pays whatever the cache holds.
print(f"median of {repetitions}: the warm run's pair stage took "
      f"{100 * statistics.median(warm_pairs_share):.1f} % of the cold run, the rest of the warm "
      f"run {100 * statistics.median(warm_rest_share):.1f} %; its CPU time (user + system) per "
      f"core {100 * statistics.median(warm_cpu_share):.1f} % (the least it could take with "
      f"all {os.cpu_count()} cores busy throughout)")
PY
