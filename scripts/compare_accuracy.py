#!/usr/bin/python3
"""Compares two runs of scripts/accuracy_sets.sh (OUT_A, OUT_B: their output folders) pair by pair.

The sets' coarse and fine counts move by whole pairs across fixed thresholds (3 cells, 1 cell), so
a change that makes most poses better can still move a pair from 0.99 to 1.01 cells. This prints,
per set, over the pairs merged in both runs: the median and mean displacement (eval's mean
displacement of map b's walls, in cells) and yaw error, and how many pairs got better or worse by
more than 0.01 cells.
Usage: scripts/compare_accuracy.py OUT_A OUT_B
"""
import glob
import json
import os
import statistics
import sys

SETS = ["held-out", "fresh", "seeds51-68", "foreign", "look-alike"]


def merged_pairs(run, name):
    """(case, a, b) -> (displacement_cells, yaw_error_deg) of the set's scored, merged pairs."""
    pairs = {}
    for path in glob.glob(os.path.join(run, name, "*", "eval.json")):
        case = os.path.basename(os.path.dirname(path))
        for p in json.load(open(path))["pairs"]:
            if p.get("scored") and p.get("merged"):
                pairs[(case, p["a"], p["b"])] = (p["displacement_cells"], p["yaw_error_deg"])
    return pairs


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__.strip().splitlines()[-1])
    run_a, run_b = sys.argv[1], sys.argv[2]
    for name in SETS:
        a, b = merged_pairs(run_a, name), merged_pairs(run_b, name)
        both = sorted(set(a) & set(b))
        if not both:
            print(f"{name}: no pair merged in both runs")
            continue
        cells_a = [a[k][0] for k in both]
        cells_b = [b[k][0] for k in both]
        yaw_a = [a[k][1] for k in both]
        yaw_b = [b[k][1] for k in both]
        better = sum(1 for k in both if b[k][0] < a[k][0] - 0.01)
        worse = sum(1 for k in both if b[k][0] > a[k][0] + 0.01)
        print(f"{name}: {len(both)} pairs merged in both; displacement median "
              f"{statistics.median(cells_a):.3f} -> {statistics.median(cells_b):.3f} cells, mean "
              f"{statistics.mean(cells_a):.3f} -> {statistics.mean(cells_b):.3f}; yaw median "
              f"{statistics.median(yaw_a):.3f} -> {statistics.median(yaw_b):.3f} deg, mean "
              f"{statistics.mean(yaw_a):.3f} -> {statistics.mean(yaw_b):.3f}; "
              f"better {better}, worse {worse}")


if __name__ == "__main__":
    main()
