#!/usr/bin/python3
"""Every accepted bridge edge (the only link between two groups of maps) of simulated cases, with
its omega, overlap and wall agreement, and whether the truth puts it within 2 degrees and 0.5 m.
Usage: scripts/bridges.py CASE_DIR...   (folders of `fleetmerge simulate` merged with their job)
The data behind min_bridge_wall_agreement (docs/accuracy.md, "Lone links")."""
import json, math, os, re, sys


def compose(p, q):
    x, y, t = p
    c, s = math.cos(t), math.sin(t)
    return (x + c * q[0] - s * q[1], y + s * q[0] + c * q[1], t + q[2])


def inverse(p):
    x, y, t = p
    c, s = math.cos(t), math.sin(t)
    return (-c * x - s * y, s * x - c * y, -t)


def truth_poses(path):
    maps = {}
    pattern = (r"\s*- \{name: (\S+), file: \S+, building: (\S+), resolution: \S+, "
               r"pose: \{x: (\S+), y: (\S+), yaw: (\S+)\}\}")
    for line in open(path):
        m = re.match(pattern, line)
        if m:
            maps[m.group(1)] = (m.group(2), tuple(float(m.group(k)) for k in (3, 4, 5)))
    return maps


def connected(edges, start, goal):
    seen, stack = {start}, [start]
    while stack:
        x = stack.pop()
        for a, b in edges:
            for u, v in ((a, b), (b, a)):
                if u == x and v not in seen:
                    seen.add(v)
                    stack.append(v)
    return goal in seen


for case in (c for c in sys.argv[1:] if os.path.isdir(c)):
    truth = truth_poses(os.path.join(case, "truth.yaml"))
    report = json.load(open(os.path.join(case, "merged", "report.json")))
    accepted = [p for p in report["pairs"] if p["accepted"]]
    for e in accepted:
        others = [(p["a"], p["b"]) for p in accepted if p is not e]
        if connected(others, e["a"], e["b"]):
            continue
        h = e["hypotheses"][e["edge_hypothesis"]]
        right = False
        if truth[e["a"]][0] == truth[e["b"]][0]:
            T = compose(inverse(truth[e["a"]][1]), truth[e["b"]][1])
            d = compose(inverse(T), (h["x"], h["y"], h["yaw"]))
            yaw = (d[2] + math.pi) % (2 * math.pi) - math.pi
            right = abs(yaw) < math.radians(2) and math.hypot(d[0], d[1]) < 0.5
        print("right" if right else "WRONG", os.path.basename(case), e["a"], e["b"],
              "omega %.3f overlap %d walls %.3f" % (e["omega"], e["overlap_cells"],
                                                     e["wall_agreement"]))
