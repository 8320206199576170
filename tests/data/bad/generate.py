#!/usr/bin/env python3
"""Writes the catalogue of malformed inputs in this folder: one folder per case holding the
input files and case.txt (reader, input, the text its error must contain). Run from anywhere;
the files are checked in, this script documents how each was made and rebuilds them.
tests/io/bad_inputs_test.cpp runs every case; fuzzer regressions live in tests/fuzz/regressions.
"""
import os
import shutil
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
GOOD_MAP = ("image: {image}\nresolution: 0.05\norigin: [0.0, 0.0, 0.0]\nnegate: 0\n"
            "occupied_thresh: 0.65\nfree_thresh: 0.196\n")


def png(width, height, rows=None, colour_type=0, bit_depth=8, ihdr=None):
    def chunk(kind, data):
        return (struct.pack(">I", len(data)) + kind + data +
                struct.pack(">I", zlib.crc32(kind + data) & 0xffffffff))
    if rows is None:
        rows = [bytes([254] * width) for _ in range(height)]
    raw = b"".join(b"\x00" + r for r in rows)
    header = ihdr or struct.pack(">IIBBBBB", width, height, bit_depth, colour_type, 0, 0, 0)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(raw)) +
            chunk(b"IEND", b""))


GOOD_PNG = png(4, 3)
GOOD_PGM = b"P5\n4 3\n255\n" + bytes([0, 254, 205, 254, 254, 254, 0, 205, 205, 0, 254, 254])

# name: (reader, {file: bytes}, input, expected error text)
CASES = {}


def map_case(name, image_bytes, expect, image="map.pgm", yaml=None):
    files = {"map.yaml": (yaml if yaml is not None else GOOD_MAP.format(image=image)).encode()
             if isinstance(yaml, (str, type(None))) else yaml}
    if image_bytes is not None:
        files[image] = image_bytes
    CASES[name] = ("map", files, "map.yaml", expect)


# --- images ---------------------------------------------------------------------------------
map_case("pgm_truncated_pixels", GOOD_PGM[:-5], "is truncated")
map_case("pgm_header_only", b"P5\n4 3\n255\n", "is truncated")
map_case("pgm_cut_in_header", b"P5\n4 3\n25", "is truncated")  # maxval 25, then nothing
map_case("pgm_cut_in_size", b"P5\n4 3", "malformed or incomplete Netpbm")
map_case("pgm_huge_size", b"P5\n100000 100000\n255\n" + bytes(64), "more than the limit")
map_case("pgm_negative_size", b"P5\n-4 3\n255\n" + bytes(12), "malformed or incomplete Netpbm")
map_case("pgm_absurd_digits", b"P5\n99999999999 3\n255\n" + bytes(12),
         "malformed or incomplete Netpbm")
map_case("pgm_zero_width", b"P5\n0 3\n255\n", "is an empty image")
map_case("pgm_maxval_zero", b"P5\n4 3\n0\n" + bytes(12), "has maxval 0")
map_case("pgm_maxval_too_big", b"P5\n4 3\n70000\n" + bytes(24), "has maxval 70000")
map_case("pgm_16bit_truncated", b"P5\n4 3\n65535\n" + bytes(20), "is truncated")
map_case("pgm_wrong_magic", b"P9\n4 3\n255\n" + bytes(12), "is not a PGM or PNG image")
map_case("pgm_lowercase_magic", b"p5\n4 3\n255\n" + bytes(12), "is not a PGM or PNG image")
map_case("ppm_truncated", b"P6\n4 3\n255\n" + bytes(30), "is truncated")
map_case("pbm_truncated", b"P4\n16 3\n" + bytes(4), "is truncated")
map_case("p2_truncated", b"P2\n4 3\n255\n0 254 205", "is not a readable PGM/PNG image")
map_case("p2_letters", b"P2\n2 2\n255\n0 abc 3 4\n", "is not a readable PGM/PNG image")
map_case("image_empty", b"", "is empty (0 bytes)")
map_case("image_text", b"hello, this is not an image\n", "is not a PGM or PNG image")
map_case("image_jpeg_magic", b"\xff\xd8\xff\xe0" + bytes(64), "is not a PGM or PNG image",
         image="map.jpg")
map_case("image_one_byte", b"P", "is not a PGM or PNG image")
map_case("png_signature_only", GOOD_PNG[:8], "truncated or corrupt PNG")
map_case("png_cut_in_ihdr", GOOD_PNG[:20], "truncated or corrupt PNG", image="map.png")
map_case("png_cut_in_data", GOOD_PNG[:45], "is not a readable PGM/PNG image", image="map.png")
map_case("png_huge_size", png(4, 3, ihdr=struct.pack(">IIBBBBB", 100000, 100000, 8, 0, 0, 0, 0)),
         "more than the limit", image="map.png")
map_case("png_max_size", png(4, 3, ihdr=struct.pack(">IIBBBBB", 0xffffffff, 0xffffffff, 8, 0, 0,
                                                     0, 0)),
         "more than the limit", image="map.png")
map_case("png_zero_height", png(4, 3, ihdr=struct.pack(">IIBBBBB", 4, 0, 8, 0, 0, 0, 0)),
         "is an empty image", image="map.png")
corrupt = bytearray(GOOD_PNG)
corrupt[41:49] = b"\xff" * 8  # inside the compressed IDAT
map_case("png_corrupt_data", bytes(corrupt), "is not a readable PGM/PNG image", image="map.png")
map_case("png_named_pgm", GOOD_PNG, None)  # decoded by content: loads (see case.txt 'loads')
map_case("image_is_the_yaml", None, "is not a PGM or PNG image", image="map.yaml")

# --- map YAML -------------------------------------------------------------------------------
def yaml_case(name, text, expect):
    map_case(name, GOOD_PGM, expect, yaml=text)


yaml_case("yaml_empty", b"", "expected a mapping")
yaml_case("yaml_not_utf8", b"image: map.pgm\nresolution: 0.05\xff\xfe\norigin: [0, 0, 0]\n",
          "line 2, column 17: not valid UTF-8")
yaml_case("yaml_not_utf8_key", b"ima\xc3\x28ge: map.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n",
          "line 1, column 4: not valid UTF-8")
yaml_case("yaml_latin1_image_name", b"image: m\xe4p.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n",
          "not valid UTF-8")
yaml_case("yaml_overlong_utf8", b"image: map.pgm\nresolution: 0.05\xc0\xaf\norigin: [0, 0, 0]\n",
          "not valid UTF-8")
yaml_case("yaml_binary", bytes(range(256)), "not valid UTF-8")
yaml_case("yaml_nan_resolution", "image: map.pgm\nresolution: .nan\norigin: [0, 0, 0]\n",
          "expected a finite number")
yaml_case("yaml_inf_origin", "image: map.pgm\nresolution: 0.05\norigin: [.inf, 0, 0]\n",
          "expected a finite number")
yaml_case("yaml_nan_yaw", "image: map.pgm\nresolution: 0.05\norigin: [0, 0, .NaN]\n",
          "expected a finite number")
yaml_case("yaml_negative_resolution", "image: map.pgm\nresolution: -0.05\norigin: [0, 0, 0]\n",
          "expected a number > 0")
yaml_case("yaml_zero_resolution", "image: map.pgm\nresolution: 0\norigin: [0, 0, 0]\n",
          "expected a number > 0")
yaml_case("yaml_truncated", "image: map.pgm\nresolution: 0.05\norigin: [0.0, 0.",
          "malformed YAML")
yaml_case("yaml_origin_two", "image: map.pgm\nresolution: 0.05\norigin: [0, 0]\n",
          "expected a list of 3 numbers")
yaml_case("yaml_origin_text", "image: map.pgm\nresolution: 0.05\norigin: here\n",
          "expected a list of 3 numbers")
yaml_case("yaml_duplicate_key", "image: map.pgm\nresolution: 0.05\nresolution: 0.1\n"
          "origin: [0, 0, 0]\n", "resolution")
yaml_case("yaml_missing_image", "resolution: 0.05\norigin: [0, 0, 0]\n",
          "missing required key 'image'")
yaml_case("yaml_image_missing_file", "image: nowhere.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n",
          "does not exist")
yaml_case("yaml_deep_nesting", "image: map.pgm\nresolution: 0.05\norigin: " + "[" * 20000 +
          "]" * 20000 + "\n", "map.yaml")
yaml_case("yaml_list", "- image: map.pgm\n- resolution: 0.05\n", "expected a mapping")
yaml_case("yaml_thresholds_swapped", "image: map.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n"
          "occupied_thresh: 0.1\nfree_thresh: 0.9\n", "expected free_thresh < occupied_thresh")
yaml_case("yaml_threshold_nan", "image: map.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n"
          "occupied_thresh: .nan\n", "expected a finite number")

# --- job files ------------------------------------------------------------------------------
def job_case(name, text, expect, maps=("a", "b")):
    files = {"job.yaml": text.encode() if isinstance(text, str) else text}
    for m in maps:
        files[m + ".yaml"] = GOOD_MAP.format(image=m + ".pgm").encode()
        files[m + ".pgm"] = GOOD_PGM
    CASES[name] = ("job", files, "job.yaml", expect)


job_case("job_empty", "", "expected a job")
job_case("job_same_file_twice", "maps: [a.yaml, {path: ./a.yaml, name: again}]\noutput: out\n",
         "is the same file as")
job_case("job_duplicate_names", "maps:\n  - {path: a.yaml, name: r1}\n  - {path: b.yaml, name: r1}\n"
         "output: out\n", "map name 'r1' is also the name of")
job_case("job_no_maps", "maps: []\noutput: out\n", "a non-empty list of map YAML files")
job_case("job_missing_output", "maps: [a.yaml, b.yaml]\n", "missing")
job_case("job_nan_threshold", "maps: [a.yaml, b.yaml]\noutput: out\nomega_threshold: .nan\n",
         "omega_threshold")
job_case("job_inf_resolution", "maps: [a.yaml, b.yaml]\noutput: out\nresolution: .inf\n",
         "resolution")
job_case("job_negative_threads", "maps: [a.yaml, b.yaml]\noutput: out\nthreads: -3\n", "threads")
job_case("job_max_map_cells_zero", "maps: [a.yaml, b.yaml]\noutput: out\nmax_map_cells: 0\n",
         "max_map_cells")
job_case("job_max_map_cells_text", "maps: [a.yaml, b.yaml]\noutput: out\nmax_map_cells: lots\n",
         "max_map_cells")
job_case("job_huge_integer", "maps: [a.yaml, b.yaml]\noutput: out\nseed: 99999999999999999999999\n",
         "seed")
job_case("job_unknown_key", "maps: [a.yaml, b.yaml]\noutput: out\nomega_treshold: 0.9\n",
         "omega_treshold")
job_case("job_not_utf8", b"maps: [a.yaml, b.yaml]\noutput: o\xff\xfeut\nname: \xc3\x28\n",
         "not valid UTF-8")
job_case("job_truncated", "jobs:\n  - maps: [a.yaml, b.yaml]\n    output: [out", "malformed YAML")
job_case("job_missing_map_file", "maps: [a.yaml, gone.yaml]\noutput: out\n", "gone.yaml")
job_case("job_bad_map_inside", "maps: [a.yaml, bad.yaml]\noutput: out\n", "bad.yaml")
CASES["job_bad_map_inside"][1]["bad.yaml"] = b"image: a.pgm\nresolution: .nan\norigin: [0,0,0]\n"
job_case("jobs_same_output", "jobs:\n  - {maps: [a.yaml], output: out}\n"
         "  - {maps: [b.yaml], output: ./out/}\n", "is also the output folder of")
job_case("jobs_same_name", "jobs:\n  - {name: x, maps: [a.yaml], output: o1}\n"
         "  - {name: x, maps: [b.yaml], output: o2}\n", "job name 'x' is also the name of")
job_case("jobs_empty_list", "jobs: []\n", "a non-empty list of jobs")
job_case("job_reference_unknown", "maps: [a.yaml, b.yaml]\noutput: out\nreference: c\n",
         "reference")
job_case("job_deep_nesting", "maps: " + "[" * 20000 + "]" * 20000 + "\noutput: out\n", "job.yaml")
job_case("job_output_is_a_file", "maps: [a.yaml, b.yaml]\noutput: a.pgm\n",
         "exists and is not a folder")
# A site's fixed map, robots' known start poses and the re-run cache (configs/README.md).
job_case("job_fixed_pose_nan", "maps:\n  - {path: a.yaml, fixed: true, pose: [.nan, 0, 0]}\n"
         "  - b.yaml\noutput: out\n", "key 'maps[0].pose[0]': expected a finite number")
job_case("job_fixed_pose_two_numbers", "maps:\n  - {path: a.yaml, fixed: true, pose: [1, 2]}\n"
         "  - b.yaml\noutput: out\n", "got a list of 2 elements")
job_case("job_fixed_not_a_bool", "maps:\n  - {path: a.yaml, fixed: maybe}\n  - b.yaml\n"
         "output: out\n", "key 'maps[0].fixed': expected true or false")
job_case("job_pose_without_fixed", "maps:\n  - {path: a.yaml, pose: [1, 2, 0]}\n  - b.yaml\n"
         "output: out\n", "add 'fixed: true' or remove 'pose'")
job_case("job_initial_pose_on_fixed_map", "maps:\n  - {path: a.yaml, fixed: true, "
         "initial_pose: [1, 2, 0]}\n  - b.yaml\noutput: out\n", "a fixed map's pose is its 'pose'")
job_case("job_initial_pose_inf", "maps:\n  - a.yaml\n  - {path: b.yaml, "
         "initial_pose: [0, .inf, 0]}\noutput: out\n",
         "key 'maps[1].initial_pose[1]': expected a finite number")
job_case("job_sigma_negative", "maps:\n  - a.yaml\n  - {path: b.yaml, initial_pose: [0, 0, 0], "
         "initial_pose_sigma: [-1, 0.1]}\noutput: out\n",
         "key 'maps[1].initial_pose_sigma[0]': expected a finite number > 0")
job_case("job_sigma_without_initial_pose", "maps:\n  - a.yaml\n  - {path: b.yaml, "
         "initial_pose_sigma: [0.5, 0.1]}\noutput: out\n", "add 'initial_pose: [x, y, yaw]'")
job_case("job_cache_max_mb_zero",
         "maps: [a.yaml, b.yaml]\noutput: out\ncache: c\ncache_max_mb: 0\n",
         "key 'cache_max_mb': expected an integer in [1, ")
job_case("job_cache_a_list", "maps: [a.yaml, b.yaml]\noutput: out\ncache: [c]\n",
         "key 'cache': expected a cache folder")


# --- octrees (.bt, .ot) -------------------------------------------------------------------------
# Cut and corrupted from the small valid octrees OctoMap wrote through SaveOctree
# (tests/data/octree, made by write_small_octrees.cpp: 71 nodes, 48 leaves).
OCTREES = os.path.join(HERE, "..", "octree")
SMALL_BT = open(os.path.join(OCTREES, "small.bt"), "rb").read()
SMALL_OT = open(os.path.join(OCTREES, "small.ot"), "rb").read()


def octree_case(name, data, expect, file="tree.bt"):
    CASES[name] = ("octree", {file: data}, file, expect)


def header_of(tree):
    return tree[:tree.index(b"\ndata\n") + len(b"\ndata\n")]


def data_of(tree):
    return tree[len(header_of(tree)):]


octree_case("octree_valid_bt", SMALL_BT, None)
octree_case("octree_valid_ot", SMALL_OT, None, file="tree.ot")
octree_case("octree_empty_file", b"", "is empty (0 bytes)")
octree_case("octree_wrong_magic", SMALL_BT.replace(b"binary file", b"binry file", 1),
            "not an OctoMap octree: expected the first line")
octree_case("octree_text", b"P5\n4 3\n255\n" + bytes(12), "not an OctoMap octree")
octree_case("octree_ot_named_bt", SMALL_OT, "it is the other kind; rename it to .ot")
octree_case("octree_bt_named_ot", SMALL_BT, "it is the other kind; rename it to .bt",
            file="tree.ot")
octree_case("octree_colour_type", SMALL_OT.replace(b"id OcTree", b"id ColorOcTree", 1),
            "of type 'ColorOcTree'; expected 'OcTree'", file="tree.ot")
octree_case("octree_stamped_type", SMALL_BT.replace(b"id OcTree", b"id OcTreeStamped", 1),
            "of type 'OcTreeStamped'; expected 'OcTree'")
octree_case("octree_ot_without_id", SMALL_OT.replace(b"id OcTree\n", b"", 1),
            "the header has no 'id'", file="tree.ot")
octree_case("octree_absurd_size", SMALL_BT.replace(b"size 71", b"size 999999999999999999", 1),
            "the header says 999999999999999999 nodes, the data holds 71")
octree_case("octree_size_overflow", SMALL_BT.replace(b"size 71", b"size 99999999999999999999", 1),
            "header line 5: expected 'size <node count>'")
octree_case("octree_negative_size", SMALL_BT.replace(b"size 71", b"size -71", 1),
            "header line 5: expected 'size <node count>'")
octree_case("octree_size_too_small", SMALL_OT.replace(b"size 71", b"size 70", 1),
            "the header says 70 nodes, the data holds 71", file="tree.ot")
octree_case("octree_negative_resolution",
            SMALL_BT.replace(b"res 0.10000000000000001", b"res -0.1", 1),
            "header line 6: expected 'res <resolution in metres, > 0>'")
octree_case("octree_nan_resolution", SMALL_OT.replace(b"res 0.1", b"res nan", 1),
            "expected 'res <resolution in metres, > 0>'", file="tree.ot")
octree_case("octree_inf_resolution", SMALL_BT.replace(b"res 0.10000000000000001", b"res inf", 1),
            "expected 'res <resolution in metres, > 0>'")
octree_case("octree_zero_resolution", SMALL_BT.replace(b"res 0.10000000000000001", b"res 0", 1),
            "expected 'res <resolution in metres, > 0>'")
octree_case("octree_unknown_key",
            SMALL_BT.replace(b"res 0.10000000000000001", b"resolution 0.1", 1),
            "unexpected 'resolution' (expected id, size, res or data)")
octree_case("octree_data_before_res", SMALL_BT.replace(b"res 0.10000000000000001\n", b"", 1),
            "'data' before 'size' and 'res'")
octree_case("octree_no_data_line", header_of(SMALL_BT)[:-len(b"data\n")],
            "the header ends without a 'data' line")
octree_case("octree_header_only", header_of(SMALL_BT),
            "it ends inside node 1 (0 data bytes)")
octree_case("octree_data_line_at_end", header_of(SMALL_OT)[:-1],
            "it ends inside node 1 (0 data bytes)", file="tree.ot")
# OctoMap's own empty tree (writeBinaryConst of a new OcTree): size 0, no data.
octree_case("octree_empty_tree", header_of(SMALL_BT).replace(b"size 71", b"size 0", 1),
            "the octree is empty (size 0): nothing to merge")
octree_case("octree_truncated_bt", header_of(SMALL_BT) + data_of(SMALL_BT)[:40],
            "the octree data is truncated or corrupt: it ends inside node")
octree_case("octree_truncated_ot", header_of(SMALL_OT) + data_of(SMALL_OT)[:200],
            "the octree data is truncated or corrupt: it ends inside node", file="tree.ot")
octree_case("octree_garbage_after_header", header_of(SMALL_BT) + b"this is not octree data\n",
            "the octree data is truncated or corrupt")
octree_case("octree_trailing_bytes", SMALL_BT + b"\n\n",
            "2 bytes follow the end of the tree")
# 17 nested inner nodes (11 for child 0): one level deeper than an OcTree holds.
octree_case("octree_too_deep", header_of(SMALL_BT).replace(b"size 71", b"size 17", 1) +
            b"\x03\x00" * 17, "a node at depth 16 has children (an OcTree is 16 levels deep)")
octree_case("octree_inner_without_children", header_of(SMALL_BT).replace(b"size 71", b"size 2", 1)
            + b"\x03\x00\x00\x00", "an inner node at depth 1 has no children")
octree_case("octree_nan_log_odds",
            header_of(SMALL_OT) + struct.pack("<f", float("nan")) + data_of(SMALL_OT)[4:],
            "node 1 has a log-odds that is not a finite number", file="tree.ot")


# --- Bags (reader "bag": every map topic of the bag loaded, as merge --out does) -------------
# Valid bags come from independent writers (Debian's python3-rosbag; ../bags/make_bags.py's
# rosbag2 db3 writer; a minimal MCAP writer below), then are damaged. Needs /usr/bin/python3
# with python3-rosbag and the zstd tool.
import subprocess
import sys
import tempfile

BAGS = os.path.join(HERE, "..", "bags")
TINY_PGM = b"P5\n40 30\n255\n" + bytes(([254] * 13 + [0, 205]) * 80)
TINY_YAML = b"image: tiny.pgm\nresolution: 0.05\norigin: [1.0, 2.0, 0.3]\nnegate: 0\n" \
            b"occupied_thresh: 0.65\nfree_thresh: 0.196\n"


def bag_case(name, files, expect, entry="robot.bag"):
    CASES[name] = ("bag", files, entry, expect)


def with_tiny_map(run):
    with tempfile.TemporaryDirectory() as d:
        open(os.path.join(d, "tiny.pgm"), "wb").write(TINY_PGM)
        open(os.path.join(d, "tiny.yaml"), "wb").write(TINY_YAML)
        return run(d)


def make_bags(*args):
    def run(d):
        out = os.path.join(d, "out")
        subprocess.run(["/usr/bin/python3", os.path.join(BAGS, "make_bags.py")] + list(args) +
                       ["--map", os.path.join(d, "tiny.yaml"), "--out", out], check=True)
        if os.path.isdir(out):
            return {f: open(os.path.join(out, f), "rb").read() for f in os.listdir(out)}
        return open(out, "rb").read()
    return with_tiny_map(run)


def ros1_bag(write, compression="none"):
    import rosbag
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "b.bag")
        bag = rosbag.Bag(path, "w", compression=compression)
        write(bag)
        bag.close()
        return open(path, "rb").read()


def grid(width=4, height=3, resolution=0.05, cells=None):
    import rospy
    from nav_msgs.msg import OccupancyGrid
    m = OccupancyGrid()
    m.header.stamp = rospy.Time(1700000000)
    m.header.frame_id = "map"
    m.info.resolution = resolution
    m.info.width, m.info.height = width, height
    m.info.origin.orientation.w = 1.0
    m.data = cells if cells is not None else [0] * (width * height)
    return m


def at(seconds):
    import rospy
    return rospy.Time(1700000000 + seconds)


def damaged(data, magic, offset, replacement):
    i = data.index(magic) + offset
    return data[:i] + replacement + data[i + len(replacement):]


def mcap(records):
    """A minimal MCAP file (spec v0): header, the given data-section records, data end, footer."""
    def record(op, body):
        return bytes([op]) + struct.pack("<Q", len(body)) + body

    def string(s):
        return struct.pack("<I", len(s)) + s.encode()
    out = b"\x89MCAP0\r\n" + record(1, string("ros2") + string("generate.py"))
    for op, body in records:
        out += record(op, body)
    out += record(0x0F, struct.pack("<I", 0)) + record(2, struct.pack("<QQI", 0, 0, 0))
    return out + b"\x89MCAP0\r\n"


def mcap_grid_records(payload, compression="", compressed=None):
    def string(s):
        return struct.pack("<I", len(s)) + s.encode()
    schema = struct.pack("<H", 1) + string("nav_msgs/msg/OccupancyGrid") + string("ros2msg") + \
        struct.pack("<I", 0)
    channel = struct.pack("<HH", 1, 1) + string("/map") + string("cdr") + struct.pack("<I", 0)
    message = struct.pack("<HIQQ", 1, 0, 5, 5) + payload
    inner = b"".join(bytes([op]) + struct.pack("<Q", len(b)) + b
                     for op, b in ((3, schema), (4, channel), (5, message)))
    data = compressed if compressed is not None else inner
    chunk = struct.pack("<QQQI", 5, 5, len(inner), 0) + string(compression) + \
        struct.pack("<Q", len(data)) + data
    return [(6, chunk)]


def add_bag_cases():
    try:
        import rosbag  # noqa: F401
    except ImportError:
        sys.exit("generate.py: the bag cases need Debian's python3-rosbag (/usr/bin/python3)")
    sys.path.insert(0, BAGS)
    import make_bags as bag_writer
    from std_msgs.msg import String

    good = make_bags("ros1", "--compression", "none", "--messages", "2")
    bag_case("bag_ros1_loads", {"robot.bag": good}, None)
    bag_case("bag_truncated", {"robot.bag": good[:len(good) * 2 // 3]}, "truncated bag")
    unindexed = make_bags("ros1", "--compression", "none", "--unindexed", "--messages", "2")
    bag_case("bag_truncated_unindexed", {"robot.bag": unindexed[:len(unindexed) - 700]},
             "truncated bag")
    bz2 = make_bags("ros1", "--compression", "bz2", "--messages", "2")
    bag_case("bag_corrupt_bz2", {"robot.bag": damaged(bz2, b"BZh9", 12, b"\xff" * 16)},
             "corrupt bz2 data")
    lz4 = make_bags("ros1", "--compression", "lz4", "--messages", "2")
    bag_case("bag_corrupt_lz4", {"robot.bag": damaged(lz4, b"\x04\x22\x4d\x18", 0, b"LZ5!")},
             "corrupt lz4 data")
    bag_case("bag_not_a_bag", {"robot.bag": b"this is a text file, not a bag\n"},
             "not a ROS 1 bag")
    bag_case("bag_format_1_2", {"robot.bag": b"#ROSBAG V1.2\n" + b"\0" * 64},
             "ROS bag format 1.2 is not supported")

    def chatter_only(bag):
        bag.write("/chatter", String(data="hello"), at(1))
    bag_case("bag_no_occupancy_grid", {"robot.bag": ros1_bag(chatter_only)},
             "no nav_msgs/OccupancyGrid topic; the bag has /chatter (std_msgs/String)")

    def octomap_only(bag):
        bag.write("/octomap_binary", String(data="not really an octree"), at(1),
                  connection_header={"topic": "/octomap_binary", "type": "octomap_msgs/Octomap",
                                     "md5sum": "9a45536b45c5e409cd49f04bb2d9999f",
                                     "message_definition": "bool binary\n"})
    bag_case("bag_octomap_only", {"robot.bag": ros1_bag(octomap_only)},
             "octomap_msgs topics are not read from bags (out of scope)")

    def wrong_size(bag):
        bag.write("/map", grid(4, 3, cells=[0] * 10), at(1))
    bag_case("bag_data_size_mismatch", {"robot.bag": ros1_bag(wrong_size)},
             "topic /map: data has 10 cells, expected width x height = 4 x 3 = 12")

    def nan_resolution(bag):
        bag.write("/map", grid(4, 3, resolution=float("nan")), at(1))
    bag_case("bag_nan_resolution", {"robot.bag": ros1_bag(nan_resolution)},
             "topic /map: info.resolution is nan")

    def no_cells(bag):  # a consistent message (0 x 3 cells, no data) that holds no map
        bag.write("/map", grid(0, 3, cells=[]), at(1))
    bag_case("bag_grid_without_cells", {"robot.bag": ros1_bag(no_cells)},
             "topic /map: info.width x info.height is 0 x 3: the map has no cells")

    def huge(bag):  # 1e9 cells claimed; the message holds 12
        bag.write("/map", grid(100000, 10000, cells=[0] * 12), at(1))
    bag_case("bag_grid_size_lies", {"robot.bag": ros1_bag(huge)}, "data has 12 cells")

    # ROS 2: rosbag2 SQLite (make_bags.py db3), damaged with sqlite3.
    import sqlite3

    def db3_case(name, expect, patch=None, distro="humble", entry="robot"):
        files = make_bags("db3", "--distro", distro, "--messages", "2")
        files = {("robot/" + k if k == "metadata.yaml" else "robot/" + k): v
                 for k, v in files.items()}
        files = {k.replace("out_0.db3", "robot_0.db3"): v.replace(b"out_0.db3", b"robot_0.db3")
                 if k.endswith(".yaml") else v for k, v in files.items()}
        if patch:
            files = patch(files)
        bag_case(name, files, expect, entry=entry)

    db3_case("bag_db3_humble_loads", None)
    db3_case("bag_db3_jazzy_loads", None, distro="jazzy")

    def short_cdr(files):
        with tempfile.TemporaryDirectory() as d:
            p = os.path.join(d, "x.db3")
            open(p, "wb").write(files["robot/robot_0.db3"])
            db = sqlite3.connect(p)
            db.execute("UPDATE messages SET data = substr(data, 1, 300) WHERE topic_id = "
                       "(SELECT id FROM topics WHERE name = '/map')")
            db.commit()
            db.close()
            files["robot/robot_0.db3"] = open(p, "rb").read()
        return files
    db3_case("bag_cdr_shorter_than_it_says", "topic /map: CDR payload: data needs 1200 bytes",
             short_cdr)

    def no_metadata(files):
        del files["robot/metadata.yaml"]
        return files
    db3_case("bag_folder_without_metadata", "is a folder but not a ROS 2 bag", no_metadata)

    def bad_storage(files):
        files["robot/metadata.yaml"] = files["robot/metadata.yaml"].replace(
            b"storage_identifier: sqlite3", b"storage_identifier: rosbag_v2")
        return files
    db3_case("bag_metadata_unknown_storage", "expected sqlite3 or mcap, got 'rosbag_v2'",
             bad_storage)

    def missing_file(files):
        del files["robot/robot_0.db3"]
        return files
    db3_case("bag_metadata_missing_file", "robot_0.db3' does not exist", missing_file)

    def file_compression(files):
        files["robot/metadata.yaml"] = files["robot/metadata.yaml"].replace(
            b'compression_format: ""', b"compression_format: zstd").replace(
            b'compression_mode: ""', b"compression_mode: FILE")
        return files
    db3_case("bag_db3_file_compression", "FILE compression", file_compression)
    bag_case("bag_db3_not_sqlite", {"robot.db3": b"SQLite? no, plain text\n" * 10},
             "expected a rosbag2 SQLite 3 bag", entry="robot.db3")
    bag_case("bag_plain_folder", {"robot/notes.txt": b"maps are elsewhere\n"},
             "is a folder but not a ROS 2 bag", entry="robot")

    # MCAP (a minimal writer above; CDR from make_bags.py's encoder).
    payload = bag_writer.cdr_occupancy_grid(
        5, "map", {"resolution": 0.05, "origin": [0.0, 0.0, 0.0], "width": 4, "height": 3,
                   "cells": [0] * 12})
    bag_case("bag_mcap_loads", {"robot.mcap": mcap(mcap_grid_records(payload))}, None,
             entry="robot.mcap")
    bag_case("bag_mcap_corrupt_zstd",
             {"robot.mcap": mcap(mcap_grid_records(payload, "zstd", b"\x28\xb5\x2f\xfdgarbage"))},
             "corrupt zstd data", entry="robot.mcap")
    bag_case("bag_mcap_corrupt_lz4",
             {"robot.mcap": mcap(mcap_grid_records(payload, "lz4", b"\x04\x22\x4d\x18\x00junk"))},
             "corrupt lz4 data", entry="robot.mcap")
    bag_case("bag_mcap_cdr_short", {"robot.mcap": mcap(mcap_grid_records(payload[:60]))},
             "CDR payload", entry="robot.mcap")
    bag_case("bag_mcap_truncated", {"robot.mcap": mcap(mcap_grid_records(payload))[:90]},
             "truncated or corrupt", entry="robot.mcap")
    bag_case("bag_mcap_brotli", {"robot.mcap": mcap(mcap_grid_records(payload, "brotli", b"x"))},
             "unknown chunk compression 'brotli'", entry="robot.mcap")


add_bag_cases()


def main():
    for entry in os.listdir(HERE):
        if os.path.isdir(os.path.join(HERE, entry)):
            shutil.rmtree(os.path.join(HERE, entry))
    for name, (reader, files, entry, expect) in sorted(CASES.items()):
        folder = os.path.join(HERE, name)
        os.makedirs(folder)
        for file, data in files.items():
            os.makedirs(os.path.dirname(os.path.join(folder, file)), exist_ok=True)
            with open(os.path.join(folder, file), "wb") as out:
                out.write(data)
        with open(os.path.join(folder, "case.txt"), "w") as out:
            out.write(f"reader: {reader}\ninput: {entry}\n")
            out.write(f"error: {expect}\n" if expect is not None else "loads\n")
    print(f"{len(CASES)} cases written to {HERE}")


if __name__ == "__main__":
    main()
