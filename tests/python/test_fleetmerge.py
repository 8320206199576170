"""The Python module on real maps: the same numbers as the `fleetmerge` command, round trips,
ValueErrors for bad arrays, RuntimeErrors with the command's messages, the GIL released.

Run by ctest (tests/python/CMakeLists.txt) with Debian's /usr/bin/python3 -m pytest; the
environment gives FLEETMERGE_EXECUTABLE, FLEETMERGE_SHARED_MAPS and PYTHONPATH.
"""

import json
import math
import os
import re
import subprocess
import sys
import threading
import types
from pathlib import Path

import numpy as np
import pytest

import fleetmerge

MAPS = Path(os.environ.get("FLEETMERGE_SHARED_MAPS", "../shared/data/maps"))
CLI = os.environ.get("FLEETMERGE_EXECUTABLE", "fleetmerge")
EXAMPLES = Path(__file__).resolve().parents[2] / "examples" / "python"

needs_maps = pytest.mark.skipif(
    not (MAPS / "robotis_corridor_run1.yaml").exists(),
    reason=f"real maps not found in {MAPS} (../shared/data/maps beside the repository)")


def real(name):
    return str(MAPS / f"{name}.yaml")


def cli(*args, check=True):
    # Under the sanitizers the interpreter runs with clang's shared ASan runtime preloaded
    # (tests/python/CMakeLists.txt); the command has its own, linked in.
    env = {k: v for k, v in os.environ.items() if k != "LD_PRELOAD"}
    run = subprocess.run([CLI, *args], capture_output=True, text=True, env=env)
    if check and run.returncode != 0:
        raise AssertionError(f"fleetmerge {' '.join(args)} failed: {run.stderr}")
    return run


def without_timing(report):
    report = dict(report)
    report.pop("timing_ms")
    return report


# --- pair and merge equal the command line ------------------------------------------------------

@needs_maps
@pytest.mark.parametrize("a,b", [("robotis_corridor_run1", "robotis_corridor_run2"),
                                 ("lab_pair_demo_1", "lab_pair_demo_2")])
def test_pair_equals_cli_json(a, b):
    expected = json.loads(cli("pair", "--json", "-n", "5", real(a), real(b)).stdout)
    got = fleetmerge.pair(real(a), real(b), n=5)
    assert len(got) == len(expected["hypotheses"]) == 5
    for h, e in zip(got, expected["hypotheses"]):
        # JSON prints doubles with round-trip precision: the numbers are the very same.
        assert (h.x, h.y, h.yaw, h.omega) == (e["x"], e["y"], e["yaw"], e["omega"])
        assert (h.overlap_cells, h.wall_agreement) == (e["overlap_cells"], e["wall_agreement"])
    assert got.ambiguous == expected["ambiguous"]
    assert got.margin == expected["margin"] or (math.isinf(got.margin) and expected["margin"] is None)
    assert len(got.hypotheses) == len(got) and got[-1].omega == got.hypotheses[-1].omega
    # Maps in memory give what their files give.
    in_memory = fleetmerge.pair(fleetmerge.load_map(real(a)), fleetmerge.load_map(real(b)), n=5)
    assert [(h.x, h.y, h.yaw, h.omega) for h in in_memory] == \
        [(h.x, h.y, h.yaw, h.omega) for h in got]


@needs_maps
def test_merge_equals_cli_report(tmp_path):
    paths = [real(f"robotis_corridor_run{k}") for k in (1, 2, 3)]
    cli("merge", "--quiet", "--out", str(tmp_path / "cli"), *paths)
    expected = json.loads((tmp_path / "cli" / "report.json").read_text())

    result = fleetmerge.merge(paths, out=tmp_path / "py")
    written = json.loads((tmp_path / "py" / "report.json").read_text())
    assert without_timing(result.report) == without_timing(expected)
    assert without_timing(written) == without_timing(expected)
    # The three real runs of one corridor form one building (issue 3's measured edges).
    assert len(expected["components"]) == 1
    assert sum(p["accepted"] for p in expected["pairs"]) >= 2

    # .merged holds the merged map that was written, cell for cell.
    assert len(result.merged) == 1
    on_disk = fleetmerge.load_map(tmp_path / "py" / "merged_0.yaml")
    assert np.array_equal(result.merged[0].data, on_disk.data)
    assert result.merged[0].origin == pytest.approx(on_disk.origin, abs=1e-9)
    assert result.merged[0].resolution == pytest.approx(on_disk.resolution)

    # Without out= nothing is written and the numbers are the same.
    quiet = fleetmerge.merge(paths)
    assert quiet.out is None
    assert without_timing(quiet.report) == without_timing(expected)


@needs_maps
def test_merge_of_files_takes_fixed_maps_and_initial_poses_by_name(tmp_path):
    # As `merge --fixed NAME=... --initial-pose NAME=...`: the same report (configs/
    # site_with_priors.yaml's poses: run4 overlaps nobody and is placed at its prior).
    paths = [real(f"robotis_corridor_run{k}") for k in (1, 2, 3, 4)]
    cli("merge", "--quiet", "--out", str(tmp_path / "cli"), *paths,
        "--fixed", "robotis_corridor_run1=10,5,0",
        "--initial-pose", "robotis_corridor_run2=10.3,4.7,-0.1",
        "--initial-pose", "robotis_corridor_run4=10,5,0,1.0,0.35")
    expected = json.loads((tmp_path / "cli" / "report.json").read_text())
    result = fleetmerge.merge(paths, fixed={"robotis_corridor_run1": (10, 5, 0)},
                              initial_poses={"robotis_corridor_run2": (10.3, 4.7, -0.1),
                                             "robotis_corridor_run4": (10, 5, 0, 1.0, 0.35)})
    assert without_timing(result.report) == without_timing(expected)
    assert [m["placed_by"] for m in expected["maps"]] == ["fixed", "pairs", "pairs", "prior"]
    with pytest.raises(ValueError, match="no map is named 'run9'"):
        fleetmerge.merge(paths, fixed={"run9": (0, 0, 0)})
    with pytest.raises(ValueError, match=r"must be \(x, y, yaw\) or \(x, y, yaw, metres"):
        fleetmerge.merge(paths, initial_poses={"robotis_corridor_run2": (1, 2)})
    with pytest.raises(ValueError, match=r"initial_poses\['robotis_corridor_run2'\]\[4\] "
                                         r"\(radians\) must be a number"):
        fleetmerge.merge(paths, initial_poses={"robotis_corridor_run2": (1, 2, 0, 0.5, "x")})
    with pytest.raises(ValueError, match=r"'robotis_corridor_run2': an initial pose's sigmas "
                                         r"\[-0.500000 m"):
        fleetmerge.merge(paths, initial_poses={"robotis_corridor_run2": (1, 2, 0, -0.5, 0.1)})
    with pytest.raises(ValueError, match="fixed must be a dict"):
        fleetmerge.merge(paths, fixed=[(0, 0, 0)])
    with pytest.raises(ValueError, match="a Map carries its own"):
        fleetmerge.merge([fleetmerge.load_map(p) for p in paths[:2]],
                         fixed={"robotis_corridor_run1": (0, 0, 0)})


def test_merge_with_a_cache_reuses_the_pairs_with_the_same_result(tmp_path):
    paths = [real(f"robotis_corridor_run{k}") for k in (1, 2, 3)]
    plain = fleetmerge.merge(paths)
    cold = fleetmerge.merge(paths, cache_dir=tmp_path / "cache")
    warm = fleetmerge.merge(paths, cache_dir=str(tmp_path / "cache"), cache_max_mb=16)
    assert (cold.report["cache"]["pairs_cached"], cold.report["cache"]["pairs_computed"]) == (0, 3)
    assert (warm.report["cache"]["pairs_cached"], warm.report["cache"]["pairs_computed"]) == (3, 0)
    assert warm.report["cache"]["max_mb"] == 16
    without_cache = lambda r: {k: v for k, v in without_timing(r).items() if k != "cache"}
    assert without_cache(warm.report) == without_cache(plain.report)
    assert np.array_equal(warm.merged[0].data, plain.merged[0].data)
    (tmp_path / "file").write_text("not a folder")
    with pytest.raises(RuntimeError, match="cache folder .*file exists and is not a folder"):
        fleetmerge.merge(paths, cache_dir=tmp_path / "file")


def test_pair_refuses_a_cache_it_would_ignore(tmp_path):
    a = fleetmerge.Map(np.zeros((4, 4), dtype=np.int8), 0.05)
    for key, value in (("cache_dir", tmp_path / "cache"), ("cache_max_mb", 16)):
        with pytest.raises(ValueError, match=f"pair\\(\\) has no cache: '{key}' is an option of merge"):
            fleetmerge.pair(a, a, **{key: value})
    assert not (tmp_path / "cache").exists()


@needs_maps
def test_merge_of_maps_in_memory_places_them_as_from_files():
    names = ["robotis_corridor_run1", "robotis_corridor_run2", "robotis_corridor_run3"]
    from_files = fleetmerge.merge([real(n) for n in names]).report
    maps = [fleetmerge.load_map(real(n)) for n in names]
    in_memory = fleetmerge.merge(maps, threads=1).report
    assert [m["name"] for m in in_memory["maps"]] == names
    for f, m in zip(from_files["maps"], in_memory["maps"]):
        assert m["component"] == f["component"]
        assert m["pose"] == f["pose"]
        assert m["source"] == ""
    assert [p["accepted"] for p in in_memory["pairs"]] == \
        [p["accepted"] for p in from_files["pairs"]]


def compose(a, b):
    """(x, y, yaw) of a * b."""
    c, s = math.cos(a[2]), math.sin(a[2])
    return (a[0] + c * b[0] - s * b[1], a[1] + s * b[0] + c * b[1], a[2] + b[2])


@needs_maps
def test_a_fixed_map_never_moves_and_the_others_follow_it():
    base = fleetmerge.load_map(real("robotis_corridor_run2"))
    robot = fleetmerge.load_map(real("robotis_corridor_run3"))
    free = fleetmerge.merge([base, robot], threads=1).report  # base at identity
    assert free["maps"][1]["component"] == free["maps"][0]["component"]
    pose = (3.0, -1.5, 0.4)
    base.fixed = True
    base.pose = pose
    assert base.fixed and base.pose == pose
    # A fixed map need not be first. The robot's pose is the free merge's composed with the
    # base's pose, to the pose graph's solver tolerance (the pair is now solved as robot-base).
    fixed = fleetmerge.merge([robot, base], threads=1).report
    got_base, got_robot = fixed["maps"][1]["pose"], fixed["maps"][0]["pose"]
    assert [m["fixed"] for m in fixed["maps"]] == [False, True]
    assert (got_base["x"], got_base["y"], got_base["yaw"]) == pytest.approx(pose, abs=1e-12)
    expected = compose(pose, [free["maps"][1]["pose"][k] for k in ("x", "y", "yaw")])
    assert (got_robot["x"], got_robot["y"]) == pytest.approx(expected[:2], abs=1e-6)
    assert math.remainder(got_robot["yaw"] - expected[2], 2 * math.pi) == pytest.approx(0, abs=1e-6)
    as_keywords = fleetmerge.Map(robot.data, robot.resolution, robot.origin, fixed=True,
                                 pose=(1, 2, 3))
    assert as_keywords.fixed and as_keywords.pose == (1, 2, 3)
    # As a job file: `fixed` is a boolean, a pose needs fixed, yaws are radians.
    for loose in (1, None, "yes"):
        with pytest.raises(ValueError, match="fixed must be True or False"):
            fleetmerge.Map(robot.data, robot.resolution, fixed=loose)
    with pytest.raises(ValueError, match="a pose is the pose of a fixed map"):
        fleetmerge.Map(robot.data, robot.resolution, pose=(1, 2, 3))
    with pytest.raises(ValueError, match="90 rad looks like degrees"):
        fleetmerge.Map(robot.data, robot.resolution, fixed=True, pose=(1, 2, 90))
    as_keywords.fixed = False  # unfixed, it has no pose
    assert as_keywords.pose == (0, 0, 0)
    with pytest.raises(ValueError, match=r"pose\[1\] must be finite"):
        base.pose = (0.0, float("nan"), 0.0)
    with pytest.raises(ValueError, match="pose must be \\(x, y, yaw\\): 3 numbers, got 2"):
        base.pose = (0.0, 1.0)
    with pytest.raises(ValueError, match="must be the first fixed map"):
        fleetmerge.merge([robot, base], reference=robot.name)


@needs_maps
def test_initial_poses_refuse_contradicting_pairs_and_place_maps():
    base = fleetmerge.load_map(real("robotis_corridor_run2"))
    robot = fleetmerge.load_map(real("robotis_corridor_run3"))
    free = fleetmerge.merge([base, robot], threads=1).report
    assert free["pairs"][0]["accepted"]
    site_pose = (3.0, -1.5, 0.4)
    base.fixed = True
    base.pose = site_pose
    truth = compose(site_pose, [free["maps"][1]["pose"][k] for k in ("x", "y", "yaw")])
    # A prior 0.3 m and 5 deg off with the default sigmas (0.5 m, 10 deg): the pair decides.
    robot.initial_pose = (truth[0] + 0.3, truth[1], truth[2] + math.radians(5))
    assert robot.initial_pose_sigma == pytest.approx((0.5, math.radians(10)))
    near = fleetmerge.merge([base, robot], threads=1).report
    assert near["pairs"][0]["accepted"]
    assert [m["placed_by"] for m in near["maps"]] == ["fixed", "pairs"]
    got = near["maps"][1]["pose"]
    assert (got["x"], got["y"]) == pytest.approx(truth[:2], abs=0.05)
    assert near["maps"][1]["initial_pose"]["x"] == pytest.approx(truth[0] + 0.3)
    # A prior 5 m off with sigma 0.2 m: the pair is refused, naming the priors; the robot is
    # placed at its prior.
    wrong = (truth[0] + 3.0, truth[1] - 4.0, truth[2])
    robot = fleetmerge.Map(robot.data, robot.resolution, robot.origin, name=robot.name,
                           initial_pose=wrong, initial_pose_sigma=(0.2, math.radians(10)))
    refused = fleetmerge.merge([base, robot], threads=1).report
    pair = refused["pairs"][0]
    assert not pair["accepted"]
    assert pair["note"].startswith(
        "refused: every hypothesis contradicts the fixed pose of map 'robotis_corridor_run2' and "
        "initial_pose of map 'robotis_corridor_run3'")
    assert refused["maps"][1]["placed_by"] == "prior"
    got = refused["maps"][1]["pose"]
    assert (got["x"], got["y"], got["yaw"]) == pytest.approx(wrong, abs=1e-9)
    assert refused["maps"][1]["initial_pose_sigma"] == pytest.approx([0.2, math.radians(10)])
    with pytest.raises(ValueError, match="initial_pose_sigma is the uncertainty of an initial_pose"):
        fleetmerge.Map(robot.data, robot.resolution, initial_pose_sigma=(0.5, 0.1))
    assert fleetmerge.Map(robot.data, robot.resolution).initial_pose_sigma is None
    with pytest.raises(ValueError, match=r"initial_pose\[1\] must be finite"):
        robot.initial_pose = (0.0, float("nan"), 0.0)
    with pytest.raises(ValueError, match=r"initial_pose_sigma\[0\] must be finite and > 0"):
        robot.initial_pose_sigma = (-1.0, 0.1)
    robot.initial_pose = None
    assert robot.initial_pose is None


@needs_maps
def test_merge_options_reach_the_job():
    paths = [real("robotis_corridor_run1"), real("robotis_corridor_run2")]
    # An omega threshold no pair reaches leaves both maps unmerged, as on the command line.
    report = fleetmerge.merge(paths, omega_threshold=1.0, reference="robotis_corridor_run2").report
    assert len(report["components"]) == 2
    assert not any(p["accepted"] for p in report["pairs"])
    with pytest.raises(ValueError, match="unknown option 'omega'"):
        fleetmerge.merge(paths, omega=0.5)
    with pytest.raises(ValueError, match="fusion must be log-odds, max or vote"):
        fleetmerge.merge(paths, fusion="mean")


# --- maps: load, build, save ----------------------------------------------------------------------

@needs_maps
def test_load_map_reads_the_yaml():
    m = fleetmerge.load_map(real("robotis_corridor_run1"))
    assert m.name == "robotis_corridor_run1"
    assert m.resolution == pytest.approx(0.05)
    assert m.origin == pytest.approx((-10.0, -10.0, 0.0))
    assert m.data.dtype == np.int8 and m.data.shape == (m.height, m.width) == (384, 384)
    assert set(np.unique(m.data)) <= {-1, 0, 100}
    # Row 0 is the image's bottom row (map_server flips): compare with the PGM read by hand.
    pgm = (MAPS / "robotis_corridor_run1.pgm").read_bytes()
    lines = [line for line in pgm.split(b"\n", 4)[:4] if not line.startswith(b"#")]
    width, height = map(int, lines[1].split())
    pixels = np.frombuffer(pgm[-width * height:], dtype=np.uint8).reshape(height, width)
    occupied = (255 - pixels[-1].astype(float)) / 255 > 0.65
    assert np.array_equal(m.data[0] == 100, occupied)


@needs_maps
def test_save_and_load_round_trip(tmp_path):
    m = fleetmerge.load_map(real("lab_pair_demo_1"))
    fleetmerge.save_map(m, tmp_path / "copy.yaml")
    back = fleetmerge.load_map(tmp_path / "copy.yaml")
    assert np.array_equal(back.data, m.data)
    assert back.origin == pytest.approx(m.origin)
    assert back.resolution == pytest.approx(m.resolution)
    assert (tmp_path / "copy.pgm").exists()


def test_map_from_occupancy_grid_values():
    data = np.full((20, 30), -1, dtype=np.int8)
    data[5, :] = 100     # a wall along row 5 (y = 5.5 cells from the origin)
    data[6:, :] = 0
    data[0, 0] = 66      # above map_server's occupied_thresh 0.65: occupied
    data[0, 1] = 65      # not above it: unknown
    data[0, 2] = 19      # below free_thresh 0.196: free
    m = fleetmerge.Map(data, 0.1, (1.0, -2.0, 0.5), name="grid")
    assert (m.width, m.height, m.name) == (30, 20, "grid")
    assert m.origin == (1.0, -2.0, 0.5)
    assert np.array_equal(m.data, data)  # kept as given


def test_map_help_names_the_constructors_arguments():
    # help(fleetmerge.Map) leads with the constructor; its argument names must be the real ones.
    def names(signature):
        inner = signature[signature.index("(") + 1:signature.rindex(")")]
        inner = re.sub(r"\([^()]*\)", "", inner)  # default tuples hold commas
        args = [a.split(":")[0].split("=")[0].strip() for a in inner.split(",")]
        return [a for a in args if a not in ("self", "*")]
    documented = fleetmerge.Map.__doc__.split("\n\n")[0].replace("\n", " ")
    actual = fleetmerge.Map.__init__.__doc__.strip().splitlines()[0]
    assert names(documented) == names(actual)
    assert "initial_pose_sigma" in names(documented)


def test_saved_map_is_trinary(tmp_path):
    data = np.array([[66, 65, 19, -1], [100, 0, 50, 20]], dtype=np.int8)
    fleetmerge.save_map(fleetmerge.Map(data, 0.05), tmp_path / "m.yaml")
    back = fleetmerge.load_map(tmp_path / "m.yaml")
    assert back.data.tolist() == [[100, -1, 0, -1], [100, 0, -1, -1]]


# --- bad input ---------------------------------------------------------------------------------

@pytest.mark.parametrize("data,message", [
    (np.zeros((4, 4), dtype=np.float64), "dtype int8"),
    (np.zeros((4, 4), dtype=np.uint8), "dtype int8"),
    (np.zeros((4, 4), dtype=np.int16), "dtype int8"),
    (np.zeros(16, dtype=np.int8), "2-D"),
    (np.zeros((2, 4, 4), dtype=np.int8), "2-D"),
    (np.zeros((8, 8), dtype=np.int8)[:, ::2], "C-contiguous"),
    (np.zeros((8, 8), dtype=np.int8).T[:, :3], "C-contiguous"),
    (np.zeros((0, 4), dtype=np.int8), "at least one cell"),
    (np.full((3, 3), 101, dtype=np.int8), "-1 \\(unknown\\) or 0..100"),
    (np.full((3, 3), -2, dtype=np.int8), "-1 \\(unknown\\) or 0..100"),
    ([[0, 0], [0, 0]], "numpy array"),
])
def test_bad_arrays_are_value_errors(data, message):
    with pytest.raises(ValueError, match=message):
        fleetmerge.Map(data, 0.05, (0, 0, 0))


@pytest.mark.parametrize("resolution,origin,message", [
    (float("nan"), (0, 0, 0), "resolution must be a finite number > 0"),
    (float("inf"), (0, 0, 0), "resolution must be a finite number > 0"),
    (0.0, (0, 0, 0), "resolution must be a finite number > 0"),
    (-0.05, (0, 0, 0), "resolution must be a finite number > 0"),
    ("0.05", (0, 0, 0), "resolution must be a number"),
    (0.05, (0, float("nan"), 0), "origin\\[1\\] must be finite"),
    (0.05, (0, 0, float("inf")), "origin\\[2\\] must be finite"),
    (0.05, (0, 0), "3 numbers, got 2"),
    (0.05, "xyz", "sequence"),
    (0.05, (0, "a", 0), "origin\\[1\\] must be a number"),
])
def test_bad_resolution_and_origin_are_value_errors(resolution, origin, message):
    with pytest.raises(ValueError, match=message):
        fleetmerge.Map(np.zeros((4, 4), dtype=np.int8), resolution, origin)


def test_bad_file_errors_carry_the_cli_message(tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text("image: missing.pgm\nresolution: .nan\norigin: [0, 0, 0]\n")
    other = tmp_path / "other.yaml"
    other.write_text("image: missing.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n")
    run = cli("pair", str(bad), str(other), check=False)
    assert run.returncode == 1
    cli_message = run.stderr.strip().removeprefix("fleetmerge: error: ")
    with pytest.raises(RuntimeError) as error:
        fleetmerge.load_map(bad)
    assert str(error.value) == cli_message
    assert str(bad) in str(error.value)
    with pytest.raises(RuntimeError, match="missing"):
        fleetmerge.pair(bad, other)
    with pytest.raises(ValueError, match="Map or a path"):
        fleetmerge.pair(42, other)


def test_duplicate_names_and_bad_reference_are_value_errors():
    m = fleetmerge.Map(np.zeros((4, 4), dtype=np.int8), 0.05, name="same")
    with pytest.raises(ValueError, match="two maps are named 'same'"):
        fleetmerge.merge([m, m])
    with pytest.raises(ValueError, match="reference 'nope'"):
        fleetmerge.merge([m], reference="nope")


# --- threads -------------------------------------------------------------------------------------

@needs_maps
def test_gil_is_released_while_merging():
    paths = [real(f"robotis_corridor_run{k}") for k in (1, 2, 3)]
    done = threading.Event()
    results = []

    def work():
        results.append(fleetmerge.merge(paths, threads=1))
        done.set()

    worker = threading.Thread(target=work)
    worker.start()
    ticks = 0
    while not done.is_set():  # runs only while the worker does not hold the GIL
        ticks += 1
    worker.join()
    assert results and len(results[0].report["maps"]) == 3
    # A merge of three maps takes hundreds of milliseconds; a held GIL would leave this loop a
    # handful of iterations at most (the interpreter switches every 5 ms only between bytecodes).
    assert ticks > 10000


# --- the README's ROS 2 conversion -----------------------------------------------------------------

def fake_occupancy_grid():
    """An object with nav_msgs/msg/OccupancyGrid's fields (no rclpy needed)."""
    ns = types.SimpleNamespace
    point = ns(x=0.0, y=0.0, z=0.0)
    quaternion = ns(x=0.0, y=0.0, z=0.0, w=1.0)
    info = ns(resolution=0.0, width=0, height=0, origin=ns(position=point, orientation=quaternion))
    return ns(header=ns(frame_id="", stamp=None), info=info, data=[])


@needs_maps
def test_ros2_occupancy_grid_round_trip():
    sys.path.insert(0, str(EXAMPLES))
    try:
        from ros2_occupancy_grid import map_from_msg, msg_from_map
    finally:
        sys.path.pop(0)
    m = fleetmerge.load_map(real("lab_pair_demo_2"))
    rotated = fleetmerge.Map(m.data, m.resolution, (m.origin[0], m.origin[1], 0.7), name="r")
    msg = msg_from_map(rotated, fake_occupancy_grid(), frame_id="robot2/map")
    assert msg.info.width == m.width and len(msg.data) == m.width * m.height
    assert all(isinstance(v, int) for v in msg.data[:10])
    back = map_from_msg(msg, name="r")
    assert np.array_equal(back.data, m.data)
    assert back.origin == pytest.approx((m.origin[0], m.origin[1], 0.7))
    assert math.isclose(back.resolution, m.resolution)


@needs_maps
def test_readme_ros2_conversion_runs():
    """The README's conversion code, as printed there, on message-shaped objects."""
    readme = (Path(__file__).resolve().parents[2] / "README.md").read_text()
    blocks = readme.split("```python\n")[1:]
    code = next(b.split("```")[0] for b in blocks if "def map_from_msg" in b)
    namespace = {}
    exec(compile(code, "README.md", "exec"), namespace)
    m = fleetmerge.load_map(real("robotis_corridor_run3"))
    shifted = fleetmerge.Map(m.data, m.resolution, (1.5, -2.0, -2.9), name="run3")
    msg = namespace["msg_from_map"](shifted, fake_occupancy_grid(), frame_id="robot3/map")
    assert msg.header.frame_id == "robot3/map"
    back = namespace["map_from_msg"](msg, name="run3")
    assert np.array_equal(back.data, m.data)
    assert back.origin == pytest.approx((1.5, -2.0, -2.9))


def test_bags_load_and_pair_as_the_cli_reads_them():
    """ROS 2 MCAP bags (written by npm's @mcap/core, tests/data/bags) read like their maps."""
    bags = Path(__file__).resolve().parents[1] / "data" / "bags" / "mcap_sim_seed3"
    from_bag = fleetmerge.load_map(bags / "robot1")
    from_file = fleetmerge.load_map(bags / "maps" / "robot1.yaml")
    assert from_bag.name == "robot1"
    assert np.array_equal(from_bag.data, from_file.data)
    assert from_bag.origin == pytest.approx(from_file.origin)
    assert from_bag.resolution == from_file.resolution
    expected = json.loads(cli("pair", "--json", str(bags / "robot1"), str(bags / "robot2")).stdout)
    got = fleetmerge.pair(bags / "robot1", bags / "robot2")
    assert [(h.x, h.y, h.yaw, h.omega) for h in got] == \
        [(e["x"], e["y"], e["yaw"], e["omega"]) for e in expected["hypotheses"]]
    with pytest.raises(RuntimeError, match="not a ROS 2 bag|no such|does not exist"):
        fleetmerge.load_map(bags)  # a folder of bags is not a bag


# --- version ------------------------------------------------------------------------------------

def test_version_is_the_project_version_and_the_commands():
    """__version__ is project(VERSION) of the top CMakeLists.txt, as `fleetmerge --version` says."""
    cmake = (Path(__file__).resolve().parents[2] / "CMakeLists.txt").read_text()
    project = re.search(r"project\(fleetmerge\s+VERSION\s+(\d+\.\d+\.\d+)", cmake).group(1)
    assert fleetmerge.__version__ == project
    assert cli("--version").stdout == f"fleetmerge {project}\n"
