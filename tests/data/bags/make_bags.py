#!/usr/bin/python3
"""Writes robot bags holding map_server maps as nav_msgs/OccupancyGrid topics, with writers other
than fleetmerge's readers, for the bag tests (tests/cli/bags_cli_test.cpp) and by hand:

  ros1   ROS 1 bag by Debian's python3-rosbag (genpy serialization of python3-nav-msgs):
         uncompressed, bz2 or lz4 chunks; --unindexed leaves it as a killed recorder does
         (chunks flushed, the index and final header never written).
  db3    ROS 2 bag folder in rosbag2's SQLite 3 layout, by Python's sqlite3 and a CDR encoder
         written here from the CDR spec: --distro humble (metadata version 5, QoS as a YAML
         string, schema 3) or jazzy (version 9, QoS as a list, schema 4 with message_definitions
         and type hashes); --message-zstd compresses each message (compression mode MESSAGE)
         with the zstd tool.

Every map becomes a GMapping-like topic: --messages N messages, the first N-1 growing crops of
the map (GMapping's map grows as the robot explores, its origin moving with it), the last the
whole map; plus a /map_metadata and a /rosout-like chatter topic, so the map topic is not the
bag's only one. MAP: a map_server YAML with a binary PGM (P5, 8 bit) image, e.g. what
`fleetmerge simulate` or `fleetmerge bench cut-fleet` write. Several --map/--topic pairs put
several maps in one bag. Run with Debian's /usr/bin/python3 (python3-rosbag).
"""
import argparse
import math
import os
import sqlite3
import struct
import subprocess
import sys

NS = 1_000_000_000


def read_map(yaml_path):
    """map_server semantics (trinary, negate 0): returns resolution, origin [x, y, yaw], width,
    height and the cells as OccupancyGrid values (-1, 0, 100), bottom row first."""
    keys = {}
    for line in open(yaml_path):
        line = line.split("#")[0].strip()
        if ":" in line:
            k, v = line.split(":", 1)
            keys[k.strip()] = v.strip()
    image = os.path.join(os.path.dirname(yaml_path), keys["image"])
    origin = [float(v) for v in keys["origin"].strip("[]").split(",")]
    occupied, free = float(keys.get("occupied_thresh", 0.65)), float(keys.get("free_thresh", 0.196))
    negate = keys.get("negate", "0") in ("1", "true")
    data = open(image, "rb").read()
    fields, pos = [], 0
    while len(fields) < 4:  # P5 header: magic, width, height, maxval; '#' comments allowed
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
    assert fields[0] == b"P5" and fields[3] == b"255", image + ": expected an 8-bit binary PGM"
    width, height = int(fields[1]), int(fields[2])
    pixels = data[pos + 1:pos + 1 + width * height]
    cells = []
    for row in range(height - 1, -1, -1):  # image row 0 is the top of the map
        for v in pixels[row * width:(row + 1) * width]:
            p = v / 255.0 if negate else (255 - v) / 255.0
            cells.append(100 if p > occupied else 0 if p < free else -1)
    return {"resolution": float(keys["resolution"]), "origin": origin, "width": width,
            "height": height, "cells": cells}


def crops(m, messages):
    """GMapping-like growth: message k of n shows the central k/n of the map (by side), origin
    moved accordingly; the last is the whole map."""
    out = []
    for k in range(1, messages + 1):
        f = k / messages
        w, h = max(1, round(m["width"] * f)), max(1, round(m["height"] * f))
        i0, j0 = (m["width"] - w) // 2, (m["height"] - h) // 2
        x0, y0, yaw = m["origin"]
        r = m["resolution"]
        ox = x0 + math.cos(yaw) * i0 * r - math.sin(yaw) * j0 * r
        oy = y0 + math.sin(yaw) * i0 * r + math.cos(yaw) * j0 * r
        cells = []
        for j in range(j0, j0 + h):
            cells.extend(m["cells"][j * m["width"] + i0:j * m["width"] + i0 + w])
        out.append({"resolution": r, "origin": [ox, oy, yaw], "width": w, "height": h,
                    "cells": cells})
    return out


def quaternion(yaw):
    return (0.0, 0.0, math.sin(yaw / 2), math.cos(yaw / 2))


def write_ros1(args, maps):
    import rosbag
    import rospy
    from nav_msgs.msg import MapMetaData, OccupancyGrid
    from std_msgs.msg import String
    compression = {"none": rosbag.Compression.NONE, "bz2": rosbag.Compression.BZ2,
                   "lz4": rosbag.Compression.LZ4}[args.compression]
    if os.path.exists(args.out):
        os.remove(args.out)
    # A small chunk threshold: several chunks, so the index has to pick the right one.
    bag = rosbag.Bag(args.out, "w", compression=compression, chunk_threshold=64 * 1024)
    for t, topic, grid in timeline(args, maps):
        stamp = rospy.Time(t // NS, t % NS)
        if grid is None:
            bag.write("/chatter", String(data="robot alive %d" % (t // NS)), stamp)
            continue
        msg = OccupancyGrid()
        msg.header.stamp = stamp
        msg.header.frame_id = args.frame_id
        msg.info.map_load_time = stamp
        msg.info.resolution = grid["resolution"]
        msg.info.width, msg.info.height = grid["width"], grid["height"]
        msg.info.origin.position.x, msg.info.origin.position.y = grid["origin"][:2]
        q = quaternion(grid["origin"][2])
        o = msg.info.origin.orientation
        o.x, o.y, o.z, o.w = q
        msg.data = grid["cells"]
        bag.write(topic, msg, stamp)
        bag.write(topic + "_metadata", msg.info, stamp)
    if args.unindexed:
        bag.flush()  # the chunks reach the file; the recorder then dies before close()
        bag._file.flush()
        os._exit(0)
    bag.close()


def timeline(args, maps):
    """(receive time ns, topic, grid or None for chatter) in time order."""
    events = []
    t0 = 1_700_000_000 * NS
    for index, (topic, m) in enumerate(maps):
        for k, grid in enumerate(crops(m, args.messages)):
            events.append((t0 + (k + 1) * 5 * NS + index * 1000, topic, grid))
    for s in range(0, 5 * args.messages + 2, 2):
        events.append((t0 + s * NS + 7, "/chatter", None))
    return sorted(events, key=lambda e: e[0])


class Cdr:
    """XCDR1 little-endian writer: primitives aligned to their size from the end of the 4-byte
    encapsulation header."""

    def __init__(self):
        self.body = bytearray()

    def align(self, n):
        self.body += b"\0" * ((n - len(self.body) % n) % n)

    def put(self, fmt, *values):
        size = struct.calcsize("<" + fmt[0])
        self.align(size)
        self.body += struct.pack("<" + fmt, *values)

    def string(self, s):
        data = s.encode() + b"\0"
        self.put("I", len(data))
        self.body += data

    def bytes(self):
        return b"\x00\x01\x00\x00" + bytes(self.body)


def cdr_occupancy_grid(t, frame_id, grid):
    c = Cdr()
    c.put("i", t // NS)
    c.put("I", t % NS)
    c.string(frame_id)
    c.put("i", t // NS)
    c.put("I", t % NS)
    c.put("f", grid["resolution"])
    c.put("I", grid["width"])
    c.put("I", grid["height"])
    for v in (grid["origin"][0], grid["origin"][1], 0.0) + quaternion(grid["origin"][2]):
        c.put("d", v)
    c.put("I", len(grid["cells"]))
    c.body += struct.pack("<%db" % len(grid["cells"]), *grid["cells"])
    return c.bytes()


def cdr_string(text):
    c = Cdr()
    c.string(text)
    return c.bytes()


QOS_HUMBLE = ("- history: 3\n  depth: 0\n  reliability: 1\n  durability: 1\n  deadline:\n"
              "    sec: 2147483647\n    nsec: 4294967295\n  lifespan:\n    sec: 2147483647\n"
              "    nsec: 4294967295\n  liveliness: 1\n  liveliness_lease_duration:\n"
              "    sec: 2147483647\n    nsec: 4294967295\n  avoid_ros_namespace_conventions: false")
QOS_JAZZY = ("\n        - history: keep_last\n          depth: 1\n          reliability: reliable\n"
             "          durability: transient_local\n          deadline:\n            sec: 9223372036\n"
             "            nsec: 854775807\n          lifespan:\n            sec: 9223372036\n"
             "            nsec: 854775807\n          liveliness: automatic\n"
             "          liveliness_lease_duration:\n            sec: 9223372036\n"
             "            nsec: 854775807\n          avoid_ros_namespace_conventions: false")
OCCUPANCY_GRID_DEF = ("std_msgs/Header header\nMapMetaData info\nint8[] data\n")
FAKE_HASH = "RIHS01_" + "0" * 64


def write_db3(args, maps):
    os.makedirs(args.out, exist_ok=True)
    name = os.path.basename(os.path.normpath(args.out))
    events = timeline(args, maps)
    # --split: two storage files, as `ros2 bag record --max-bag-duration` leaves them; the
    # second holds the later half of the messages (the last map among them).
    parts = [events[:len(events) // 2], events[len(events) // 2:]] if args.split else [events]
    files = []
    types = {"/chatter": "std_msgs/msg/String"}
    for topic, _ in maps:
        types[topic] = "nav_msgs/msg/OccupancyGrid"
    counts = dict.fromkeys(types, 0)
    times = []
    for index, part in enumerate(parts):
        db_name = "%s_%d.db3" % (name, index)
        files.append(db_name)
        write_db3_file(args, os.path.join(args.out, db_name), types, part, counts, times)
    write_metadata(args, files, types, counts, times, args.distro == "jazzy")


def write_db3_file(args, db_path, types, events, counts, times):
    if os.path.exists(db_path):
        os.remove(db_path)
    jazzy = args.distro == "jazzy"
    db = sqlite3.connect(db_path)
    # rosbag2_storage_default_plugins sqlite_storage.cpp, schema 3 (Humble) / 4 (Jazzy).
    db.execute("CREATE TABLE schema(schema_version INTEGER PRIMARY KEY,ros_distro TEXT NOT NULL)")
    db.execute("INSERT INTO schema VALUES(?, ?)", (4 if jazzy else 3, args.distro))
    db.execute("CREATE TABLE metadata(id INTEGER PRIMARY KEY,metadata_version INTEGER NOT NULL,"
               "metadata TEXT NOT NULL)")
    if jazzy:
        db.execute("CREATE TABLE topics(id INTEGER PRIMARY KEY,name TEXT NOT NULL,type TEXT NOT "
                   "NULL,serialization_format TEXT NOT NULL,offered_qos_profiles TEXT NOT NULL,"
                   "type_description_hash TEXT NOT NULL)")
        db.execute("CREATE TABLE message_definitions(id INTEGER PRIMARY KEY,topic_type TEXT NOT "
                   "NULL,encoding TEXT NOT NULL,encoded_message_definition TEXT NOT NULL,"
                   "type_description_hash TEXT NOT NULL)")
    else:
        db.execute("CREATE TABLE topics(id INTEGER PRIMARY KEY,name TEXT NOT NULL,type TEXT NOT "
                   "NULL,serialization_format TEXT NOT NULL,offered_qos_profiles TEXT NOT NULL)")
    db.execute("CREATE TABLE messages(id INTEGER PRIMARY KEY,topic_id INTEGER NOT NULL,timestamp "
               "INTEGER NOT NULL,data BLOB NOT NULL)")
    db.execute("CREATE INDEX timestamp_idx ON messages (timestamp ASC)")
    topics = {}
    for topic, type_name in sorted(types.items()):
        row = [topic, type_name, "cdr", QOS_HUMBLE]
        if jazzy:
            row = [topic, type_name, "cdr", QOS_JAZZY, FAKE_HASH]
        cur = db.execute("INSERT INTO topics VALUES(NULL%s)" % (",?" * len(row)), row)
        topics[topic] = cur.lastrowid
    if jazzy:
        for type_name in sorted(set(types.values())):
            db.execute("INSERT INTO message_definitions VALUES(NULL,?,?,?,?)",
                       (type_name, "ros2msg", OCCUPANCY_GRID_DEF if "Occupancy" in type_name
                        else "string data\n", FAKE_HASH))
    for t, topic, grid in events:
        data = cdr_string("robot alive") if grid is None else cdr_occupancy_grid(
            t, args.frame_id, grid)
        if args.message_zstd:  # rosbag2 --compression-mode message: each blob a zstd frame
            data = subprocess.run(["zstd", "-q", "-c"], input=data, check=True,
                                  stdout=subprocess.PIPE).stdout
        db.execute("INSERT INTO messages VALUES(NULL,?,?,?)", (topics[topic], t, data))
        counts[topic] += 1
        times.append(t)
    db.commit()
    db.close()


def write_metadata(args, files, types, counts, times, jazzy):
    lines = ["rosbag2_bagfile_information:", "  version: %d" % (9 if jazzy else 5),
             "  storage_identifier: sqlite3", "  duration:",
             "    nanoseconds: %d" % (max(times) - min(times)), "  starting_time:",
             "    nanoseconds_since_epoch: %d" % min(times), "  message_count: %d" % len(times),
             "  topics_with_message_count:"]
    for topic, type_name in sorted(types.items()):
        lines += ["    - topic_metadata:", "        name: %s" % topic,
                  "        type: %s" % type_name, "        serialization_format: cdr"]
        if jazzy:
            lines += ["        offered_qos_profiles:" + QOS_JAZZY,
                      "        type_description_hash: %s" % FAKE_HASH]
        else:
            lines += ['        offered_qos_profiles: "%s"' % QOS_HUMBLE.replace("\n", "\\n")]
        lines += ["      message_count: %d" % counts[topic]]
    compression = ["  compression_format: zstd", "  compression_mode: MESSAGE"] \
        if args.message_zstd else ['  compression_format: ""', '  compression_mode: ""']
    lines += compression + ["  relative_file_paths:"] + ["    - %s" % f for f in files]
    lines += ["  files:"]
    for f in files:  # per-file times are not needed by readers; the bag's are repeated
        lines += ["    - path: %s" % f, "      starting_time:",
                  "        nanoseconds_since_epoch: %d" % min(times), "      duration:",
                  "        nanoseconds: %d" % (max(times) - min(times)),
                  "      message_count: %d" % len(times)]
    if jazzy:
        lines += ["  custom_data: ~", "  ros_distro: jazzy"]
    with open(os.path.join(args.out, "metadata.yaml"), "w") as f:
        f.write("\n".join(lines) + "\n")


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("kind", choices=["ros1", "db3"])
    parser.add_argument("--map", action="append", required=True, help="map_server YAML")
    parser.add_argument("--topic", action="append", help="topic per --map (default /map)")
    parser.add_argument("--out", required=True, help="the .bag file or the ROS 2 bag folder")
    parser.add_argument("--compression", choices=["none", "bz2", "lz4"], default="none")
    parser.add_argument("--unindexed", action="store_true")
    parser.add_argument("--distro", choices=["humble", "jazzy"], default="humble")
    parser.add_argument("--messages", type=int, default=3)
    parser.add_argument("--split", action="store_true", help="db3: two storage files")
    parser.add_argument("--message-zstd", action="store_true",
                        help="db3: zstd per message (rosbag2 compression mode MESSAGE)")
    parser.add_argument("--frame-id", default="map")
    args = parser.parse_args()
    topics = args.topic or ["/map"]
    if len(topics) != len(args.map):
        sys.exit("make_bags.py: give one --topic per --map")
    maps = [(topic, read_map(path)) for topic, path in zip(topics, args.map)]
    (write_ros1 if args.kind == "ros1" else write_db3)(args, maps)


if __name__ == "__main__":
    main()
