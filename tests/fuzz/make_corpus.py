#!/usr/bin/env python3
"""Writes the fuzzers' seed corpus (tests/fuzz/corpus/<target>) from tests/data: every map
fixture and every map case of the malformed catalogue becomes "<yaml>\\n#IMAGE#\\n<image bytes>"
with the YAML's image renamed image.pgm (map_fuzzer.cpp); every job case of the catalogue and a
few valid job files become job seeds (job_fuzzer.cpp writes a.yaml/b.yaml beside them); the small
valid octrees in tests/data/octree (written by OctoMap) and every octree case of the catalogue
become octree seeds (octree_fuzzer.cpp reads each as a .bt and as a .ot).

The cache seeds are entries that `fleetmerge merge --cache` writes for cache_fuzzer.cpp's two
rooms (written here as PGM maps): one pair's and each room's preparation. They need a built
fleetmerge: `make_corpus.py --fleetmerge build/cli/fleetmerge`; without it the cache seeds are
left as they are."""
import argparse
import os
import re
import shutil
import subprocess
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.join(HERE, "..", "data")


def map_seed(yaml_path):
    text = open(yaml_path, "rb").read()
    match = re.search(rb"^image:\s*(\S+)", text, re.M)
    image = b""
    if match:
        image_path = os.path.join(os.path.dirname(yaml_path), match.group(1).decode("utf-8", "replace"))
        if os.path.isfile(image_path):
            image = open(image_path, "rb").read()
        text = text[:match.start(1)] + b"image.pgm" + text[match.end(1):]
    return text + b"\n#IMAGE#\n" + image


def write_room(folder, name, first_column, width):
    """cache_fuzzer.cpp's Room(first_column, width): a PGM map of 40 rows (grid row 0, the
    bottom, is the image's last) of `width` 5 cm cells, free (254) or wall (0)."""
    rows = []
    for r in reversed(range(40)):
        row = bytearray()
        for c in range(width):
            x = first_column + c
            wall = (r in (0, 39) or x in (0, 63) or (x == 20 and r < 28) or (x == 44 and r > 12)
                    or (r == 20 and 44 < x < 58))
            row.append(0 if wall else 254)
        rows.append(bytes(row))
    with open(os.path.join(folder, name + ".pgm"), "wb") as f:
        f.write(b"P5\n%d 40\n255\n" % width + b"".join(rows))
    with open(os.path.join(folder, name + ".yaml"), "w") as f:
        f.write(f"image: {name}.pgm\nresolution: 0.05\norigin: [0.0, 0.0, 0.0]\nnegate: 0\n"
                "occupied_thresh: 0.65\nfree_thresh: 0.196\n")
    return os.path.join(folder, name + ".yaml")


def cache_seeds(fleetmerge):
    """The entry files `merge --cache` writes for the two rooms, by name."""
    with tempfile.TemporaryDirectory() as tmp:
        maps = [write_room(tmp, "room_a", 0, 48), write_room(tmp, "room_b", 16, 48)]
        cache = os.path.join(tmp, "cache")
        subprocess.run([fleetmerge, "merge", "--quiet", "--cache", cache, "--out",
                        os.path.join(tmp, "out")] + maps, check=True)
        entries = sorted(n for n in os.listdir(cache) if n.endswith(".entry"))
        return {"entry_%d" % k: open(os.path.join(cache, n), "rb").read()
                for k, n in enumerate(entries)}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--fleetmerge", help="a built fleetmerge, for the cache seeds")
    args = parser.parse_args()
    seeds = {"map": {}, "job": {}, "octree": {}, "bag": {}}
    if args.fleetmerge:
        seeds["cache"] = cache_seeds(args.fleetmerge)
    octrees = os.path.join(DATA, "octree")
    for name in sorted(os.listdir(octrees)):
        if name.endswith((".bt", ".ot")):
            seeds["octree"]["valid_" + name.replace(".", "_")] = open(
                os.path.join(octrees, name), "rb").read()
    fixtures = os.path.join(DATA, "maps")
    for name in sorted(os.listdir(fixtures)):
        if name.endswith(".yaml"):
            seeds["map"]["fixture_" + name[:-5]] = map_seed(os.path.join(fixtures, name))
    bad = os.path.join(DATA, "bad")
    for case in sorted(os.listdir(bad)):
        folder = os.path.join(bad, case)
        if not os.path.isfile(os.path.join(folder, "case.txt")):
            continue
        if os.path.isfile(os.path.join(folder, "job.yaml")):
            seeds["job"]["bad_" + case] = open(os.path.join(folder, "job.yaml"), "rb").read()
        elif os.path.isfile(os.path.join(folder, "map.yaml")):
            seeds["map"]["bad_" + case] = map_seed(os.path.join(folder, "map.yaml"))
        reader = re.search(r"^reader: (\S+)", open(os.path.join(folder, "case.txt")).read(), re.M)
        if reader and reader.group(1) == "bag":
            for root, _, names in os.walk(folder):
                for name in names:
                    if name.endswith((".bag", ".mcap", ".db3")):
                        seeds["bag"]["bad_" + case + "_" + name.replace(".", "_")] = open(
                            os.path.join(root, name), "rb").read()
        for tree in ("tree.bt", "tree.ot"):
            if os.path.isfile(os.path.join(folder, tree)):
                seeds["octree"]["bad_" + case] = open(os.path.join(folder, tree), "rb").read()
    mcap = os.path.join(DATA, "bags", "mcap_sim_seed3")
    for robot in sorted(os.listdir(mcap)):
        for name in sorted(os.listdir(os.path.join(mcap, robot))):
            if name.endswith(".mcap") and os.path.getsize(os.path.join(mcap, robot, name)) < 64000:
                seeds["bag"]["fixture_" + name.replace(".", "_")] = open(
                    os.path.join(mcap, robot, name), "rb").read()
    seeds["job"]["good_one_job"] = (b"name: pair\nmaps: [a.yaml, {path: b.yaml, name: robot_b}]\n"
                                    b"output: out\nreference: robot_b\nthreads: 2\n"
                                    b"max_map_cells: 1000\nhough: {n_theta: 90, rho_step: 2, "
                                    b"sampling: 'random:0.5'}\ntranslation: {method: spectra}\n"
                                    b"pose_graph: {loss: huber, loss_scale: 0.5}\nfusion: max\n")
    seeds["job"]["good_site_job"] = (b"name: site\nmaps:\n  - {path: a.yaml, name: site, "
                                     b"fixed: true, pose: [10.0, 5.0, 0.5]}\n  - {path: b.yaml, "
                                     b"initial_pose: [10.3, 4.7, -0.1], initial_pose_sigma: "
                                     b"[0.3, 0.1]}\noutput: out\ncache: cache\ncache_max_mb: 64\n")
    seeds["job"]["good_two_jobs"] = (b"jobs:\n  - {name: one, maps: [a.yaml], output: o1}\n"
                                     b"  - {name: two, maps: [a.yaml, b.yaml], output: o2, "
                                     b"omega_threshold: 0.8, seed: 7, refine: false}\n")
    for target, files in seeds.items():
        folder = os.path.join(HERE, "corpus", target)
        shutil.rmtree(folder, ignore_errors=True)
        os.makedirs(folder)
        for name, data in files.items():
            open(os.path.join(folder, name), "wb").write(data)
        print(f"{len(files)} {target} seeds in {folder}")


if __name__ == "__main__":
    main()
