"""Merges map files with fleetmerge's Python module and prints where each map went.

    PYTHONPATH=<prefix>/lib/python3/dist-packages /usr/bin/python3 merge_fleet.py OUT a.yaml b.yaml
"""

import sys

import fleetmerge


def main(argv):
    if len(argv) < 3:
        print("usage: merge_fleet.py OUT MAP.yaml...", file=sys.stderr)
        return 2
    out, paths = argv[1], argv[2:]
    best = fleetmerge.pair(paths[0], paths[1], n=1)[0]
    print(f"pair {paths[0]} {paths[1]}: x={best.x:.3f} y={best.y:.3f} yaw={best.yaw:.4f} "
          f"omega={best.omega:.3f}")
    result = fleetmerge.merge(paths, out=out)
    for m in result.report["maps"]:
        pose = m["pose"]
        print(f"{m['name']}: component {m['component']} at x={pose['x']:.3f} y={pose['y']:.3f} "
              f"yaw={pose['yaw']:.4f}")
    for pair in result.report["pairs"]:
        verdict = "accepted" if pair["accepted"] else "refused: " + pair.get("note", "")
        print(f"{pair['a']} - {pair['b']}: omega {pair['omega']:.3f}, {verdict}")
    for merged in result.merged:
        print(f"{merged.name}: {merged.width} x {merged.height} cells")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
