"""fleetmerge: merge the occupancy grid maps of a robot fleet (Carpin's Hough-spectrum method).

    import fleetmerge
    a = fleetmerge.load_map("robot1/map.yaml")
    best = fleetmerge.pair(a, "robot2/map.yaml")[0]   # pose of b's frame in a's, and omega
    result = fleetmerge.merge(["r1.yaml", "r2.yaml", "r3.yaml"], out="merged")
    result.report["maps"]                             # report.json's contents
    result.merged[0].data                             # numpy int8, height x width

Maps follow nav_msgs/OccupancyGrid: int8 cells, -1 unknown, 0..100 occupancy, row 0 at the
origin; origin is (x, y, yaw) of cell (0, 0)'s outer corner. Results equal the `fleetmerge`
command's for the same files and options. Errors: ValueError for bad arguments, RuntimeError with
the command's message (naming the file and what was wrong) for bad files and failed merges.
"""

import json as _json
import os as _os

from ._fleetmerge import Hypothesis, Map, Options, __version__
from . import _fleetmerge

__all__ = ["Map", "Hypothesis", "MergeResult", "load_map", "save_map", "pair", "merge",
           "__version__"]


def _path(value, what):
    if isinstance(value, (str, bytes, _os.PathLike)):
        return _os.fsdecode(_os.fspath(value))
    raise ValueError(f"{what} must be a fleetmerge.Map or a path, got {type(value).__name__}")


def _map(value, what):
    if isinstance(value, Map):
        return value
    return _fleetmerge.load_map(_path(value, what))


def _options(options):
    o = Options()
    for key, value in options.items():
        if key.startswith("_") or not hasattr(o, key):
            names = sorted(k for k in dir(o) if not k.startswith("_"))
            raise ValueError(f"unknown option '{key}'; options are: {', '.join(names)}")
        if key == "cache_dir" and isinstance(value, _os.PathLike):
            value = _os.fspath(value)
        try:
            setattr(o, key, value)
        except TypeError as e:
            raise ValueError(f"option '{key}': {e}") from None
    return o


def load_map(path):
    """A map_server YAML (with its PGM/PNG image), an OctoMap octree's floor plan (.bt, .ot) or a
    ROS 1 / ROS 2 bag with one OccupancyGrid topic (its last map)."""
    return _fleetmerge.load_map(_path(path, "path"))


def save_map(map, path):
    """Writes path (YAML) and a trinary PGM beside it, as map_saver does, each atomically."""
    if not isinstance(map, Map):
        raise ValueError(f"map must be a fleetmerge.Map, got {type(map).__name__}")
    _fleetmerge.save_map(map, _path(path, "path"))


def pair(a, b, n=4, **options):
    """The n best poses of b's map frame in a's, best first: what `fleetmerge pair --json -n N
    a b` prints. A PairHypotheses: a sequence of Hypothesis (.x .y .yaw .omega .overlap_cells
    .wall_agreement), with .ambiguous (the runner-up is a different pose the maps cannot tell
    apart: a coin toss) and .margin (the best's lead in evidence, nats; inf without a
    runner-up). a and b are Maps or paths."""
    for key in ("cache_dir", "cache_max_mb"):
        if key in options:  # ignoring it would read as "the cache did not help"
            raise ValueError(f"pair() has no cache: '{key}' is an option of merge(), which keeps "
                             "a fleet's pairs for re-runs; leave it out")
    o = _options(options)
    o.hypotheses = n
    return _fleetmerge.pair(_map(a, "a"), _map(b, "b"), o)


class MergeResult:
    """report: report.json's contents as a dict; merged: the merged Maps (one per component
    that was merged, in component order); out: the output folder or None."""

    def __init__(self, native, out):
        self.report = _json.loads(native.report_json)
        self.merged = native.merged
        self.out = out

    def __repr__(self):
        return (f"<fleetmerge.MergeResult {len(self.report['maps'])} maps, "
                f"{len(self.report['components'])} component(s), {len(self.merged)} merged>")


def merge(maps, out=None, fixed=None, initial_poses=None, **options):
    """Merges a fleet's maps (Maps or paths). All paths: exactly `fleetmerge merge --out OUT
    paths...` (maps named by file stem, octrees with their merged .bt). With out=DIR the usual
    result set (merged maps, previews, report.json) is written there, replaced as a whole.
    With paths, fixed={name: (x, y, yaw)} and initial_poses={name: (x, y, yaw) or (x, y, yaw,
    metres, radians)} give fixed maps and known start poses by map name, as `merge --fixed` and
    `--initial-pose` do; a Map carries its own (fixed, pose, initial_pose, initial_pose_sigma).
    Options are keywords: threads, omega_threshold, min_overlap_cells, min_wall_agreement,
    min_bridge_wall_agreement, hypotheses, resolution, fusion, reference, refine, translation,
    max_map_cells, octree_band_min/max, cache_dir (keep pairs' hypotheses there and reuse them:
    `merge --cache`), cache_max_mb."""
    maps = list(maps)
    o = _options(options)
    for key, given in (("fixed", fixed), ("initial_poses", initial_poses)):
        if given is not None and not isinstance(given, dict):
            raise ValueError(f"{key} must be a dict {{map name: pose}}, got {type(given).__name__}")
    for name, pose in (fixed or {}).items():
        o._fix(name, pose)
    for name, value in (initial_poses or {}).items():
        o._initial_pose(name, value)
    out_dir = "" if out is None else _path(out, "out")
    if maps and all(not isinstance(m, Map) for m in maps):
        native = _fleetmerge.merge_files([_path(m, "maps[]") for m in maps], o, out_dir)
    else:
        native = _fleetmerge.merge([_map(m, "maps[]") for m in maps], o, out_dir)
    return MergeResult(native, out)
