#!/usr/bin/python3
"""What the fixed-base scripts (scripts/fixed_base_accuracy.sh, scripts/site_days.sh) check:
- a robot's reported pose against the truth, at its map's centre (cells and degrees);
- the known cells of a fixed (base) map that a merged map changed (configs/README.md, "Fixed
  (base) maps": the merged map keeps every cell a fixed map knows). The base is given as the
  merged map of a job of the base alone: fleetmerge writes a fixed map alone as it reads it
  (trinary cells, whatever the file's own values), on its lattice moved by its pose, so both maps
  are on one lattice up to a whole-cell offset.
Usage: scripts/fixed_base_checks.py BASE_ALONE_YAML MERGED_YAML   (prints the cells changed)"""
import math, os, sys

import numpy as np
import yaml

UNKNOWN, OCCUPIED, FREE = 205, 0, 254  # the trinary values of the maps fleetmerge writes


def load_merged(yaml_path):
    """A map fleetmerge wrote: its YAML and its cells (row 0 at the top)."""
    meta = yaml.safe_load(open(yaml_path))
    data = open(os.path.join(os.path.dirname(yaml_path), meta["image"]), "rb").read()
    width, height = (int(v) for v in data.split(maxsplit=3)[1:3])  # P5 W H 255: no comments
    return meta, np.frombuffer(data[len(data) - width * height:], np.uint8).reshape(height, width)


def compose(a, b):
    """(x, y, yaw) poses: a * b."""
    c, s = math.cos(a[2]), math.sin(a[2])
    return (a[0] + c * b[0] - s * b[1], a[1] + s * b[0] + c * b[1], a[2] + b[2])


def centre_error(reported, true, map_yaml):
    """Cells and degrees between two (x, y, yaw) poses of a map fleetmerge wrote (`simulate`), at
    the centre of its image."""
    meta, cells = load_merged(map_yaml)
    r = meta["resolution"]
    centre = (meta["origin"][0] + cells.shape[1] * r / 2,
              meta["origin"][1] + cells.shape[0] * r / 2, 0.0)
    at_reported, at_true = compose(reported, centre), compose(true, centre)
    cells_off = math.hypot(at_reported[0] - at_true[0], at_reported[1] - at_true[1]) / r
    yaw = reported[2] - true[2]
    return cells_off, abs(math.degrees(math.atan2(math.sin(yaw), math.cos(yaw))))


def base_cells_changed(alone_yaml, merged_yaml):
    """The base's known cells that the merged map does not hold as they are (all of them when the
    merged map is not on the base's lattice)."""
    alone_meta, alone = load_merged(alone_yaml)
    meta, merged = load_merged(merged_yaml)
    r, yaw = meta["resolution"], meta["origin"][2]
    if alone_meta["resolution"] != r or abs(alone_meta["origin"][2] - yaw) > 1e-12:
        return int((alone != UNKNOWN).sum())
    d = np.array(alone_meta["origin"][:2]) - np.array(meta["origin"][:2])
    c, s = math.cos(yaw), math.sin(yaw)
    offset = np.array([c * d[0] + s * d[1], -s * d[0] + c * d[1]]) / r  # in merged cells
    if np.abs(offset - np.round(offset)).max() > 1e-6:
        return int((alone != UNKNOWN).sum())
    dx, dy = (int(v) for v in np.round(offset))
    rows, cols = np.nonzero(alone != UNKNOWN)
    merged_rows = merged.shape[0] - 1 - (alone.shape[0] - 1 - rows + dy)  # rows from the top
    merged_cols = cols + dx
    inside = ((merged_rows >= 0) & (merged_rows < merged.shape[0]) & (merged_cols >= 0) &
              (merged_cols < merged.shape[1]))
    same = merged[merged_rows[inside], merged_cols[inside]] == alone[rows[inside], cols[inside]]
    return int((~inside).sum() + (~same).sum())


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    print(base_cells_changed(sys.argv[1], sys.argv[2]))
