// Writes ROS 2 bag folders with MCAP storage (metadata.yaml + <name>_0.mcap) holding map_server
// maps as nav_msgs/msg/OccupancyGrid, with writers other than fleetmerge's readers: npm's
// @mcap/core (the MCAP reference writer) and @foxglove/rosmsg2-serialization (CDR); chunks
// compressed by the zstd and lz4 command-line tools (Debian's zstd, lz4).
//
//   cd tests/data/bags && npm ci && node make_mcap.mjs --map M.yaml --out DIR [--compression
//      zstd|lz4|none] [--messages N]
//
// Like make_bags.py: N messages per map, the first N-1 growing crops, the last the whole map,
// plus a /chatter topic. The checked-in bags (mcap_sim_seed3/) are made by make_mcap_fixtures.sh.
import { McapWriter } from "@mcap/core";
import { parse } from "@foxglove/rosmsg";
import { MessageWriter } from "@foxglove/rosmsg2-serialization";
import { execFileSync } from "node:child_process";
import fs from "node:fs";
import path from "node:path";

const NS = 1000000000n;

function args() {
  const out = { compression: "zstd", messages: 3, topic: "/map" };
  const argv = process.argv.slice(2);
  for (let i = 0; i < argv.length; i += 2) out[argv[i].replace(/^--/, "")] = argv[i + 1];
  out.messages = Number(out.messages);
  return out;
}

// map_server semantics (trinary, negate 0) of an 8-bit binary PGM; cells bottom row first.
function readMap(yamlPath) {
  const keys = {};
  for (const line of fs.readFileSync(yamlPath, "utf8").split("\n")) {
    const l = line.split("#")[0];
    const i = l.indexOf(":");
    if (i > 0) keys[l.slice(0, i).trim()] = l.slice(i + 1).trim();
  }
  const origin = keys.origin.replace(/[[\]]/g, "").split(",").map(Number);
  const data = fs.readFileSync(path.join(path.dirname(yamlPath), keys.image));
  const fields = [];
  let pos = 0;
  while (fields.length < 4) {
    while (/\s/.test(String.fromCharCode(data[pos]))) pos++;
    if (data[pos] === 0x23) { pos = data.indexOf(0x0a, pos) + 1; continue; }
    let end = pos;
    while (!/\s/.test(String.fromCharCode(data[end]))) end++;
    fields.push(data.subarray(pos, end).toString());
    pos = end;
  }
  if (fields[0] !== "P5" || fields[3] !== "255") throw new Error(yamlPath + ": need 8-bit P5");
  const width = Number(fields[1]), height = Number(fields[2]);
  const pixels = data.subarray(pos + 1);
  const occ = Number(keys.occupied_thresh ?? 0.65), free = Number(keys.free_thresh ?? 0.196);
  const cells = new Int8Array(width * height);
  for (let j = 0; j < height; j++) {
    for (let i = 0; i < width; i++) {
      const p = (255 - pixels[(height - 1 - j) * width + i]) / 255;
      cells[j * width + i] = p > occ ? 100 : p < free ? 0 : -1;
    }
  }
  return { resolution: Number(keys.resolution), origin, width, height, cells };
}

function crop(m, k, n) {
  const f = k / n;
  const w = Math.max(1, Math.round(m.width * f)), h = Math.max(1, Math.round(m.height * f));
  const i0 = Math.floor((m.width - w) / 2), j0 = Math.floor((m.height - h) / 2);
  const [x0, y0, yaw] = m.origin;
  const r = m.resolution;
  const cells = new Int8Array(w * h);
  for (let j = 0; j < h; j++) cells.set(m.cells.subarray((j0 + j) * m.width + i0, (j0 + j) * m.width + i0 + w), j * w);
  return {
    resolution: r, width: w, height: h, cells, yaw,
    x: x0 + Math.cos(yaw) * i0 * r - Math.sin(yaw) * j0 * r,
    y: y0 + Math.sin(yaw) * i0 * r + Math.cos(yaw) * j0 * r,
  };
}

// ROS 2 message definitions, concatenated as rosbag2's MCAP plugin writes them (ros2msg).
const DEFINITION = `std_msgs/Header header
MapMetaData info
int8[] data
================================================================================
MSG: std_msgs/Header
builtin_interfaces/Time stamp
string frame_id
================================================================================
MSG: builtin_interfaces/Time
int32 sec
uint32 nanosec
================================================================================
MSG: nav_msgs/MapMetaData
builtin_interfaces/Time map_load_time
float32 resolution
uint32 width
uint32 height
geometry_msgs/Pose origin
================================================================================
MSG: geometry_msgs/Pose
Point position
Quaternion orientation
================================================================================
MSG: geometry_msgs/Point
float64 x
float64 y
float64 z
================================================================================
MSG: geometry_msgs/Quaternion
float64 x 0
float64 y 0
float64 z 0
float64 w 1
`;

function compressor(kind) {
  if (kind === "none") return undefined;
  const tool = kind === "zstd" ? ["zstd", ["-q", "-c", "-19"]] : ["lz4", ["-q", "-c", "-9"]];
  return (chunk) => ({
    compression: kind,
    compressedData: new Uint8Array(execFileSync(tool[0], tool[1], { input: chunk })),
  });
}

class FileWritable {
  constructor(file) { this.fd = fs.openSync(file, "w"); this.size = 0n; }
  async write(buffer) { fs.writeSync(this.fd, buffer); this.size += BigInt(buffer.byteLength); }
  position() { return this.size; }
  close() { fs.closeSync(this.fd); }
}

async function main() {
  const a = args();
  const map = readMap(a.map);
  fs.mkdirSync(a.out, { recursive: true });
  const name = path.basename(path.resolve(a.out));
  const file = `${name}_0.mcap`;
  const writable = new FileWritable(path.join(a.out, file));
  const writer = new McapWriter({ writable, chunkSize: 64 * 1024, compressChunk: compressor(a.compression) });
  await writer.start({ profile: "ros2", library: "make_mcap.mjs (@mcap/core)" });
  const gridSchema = await writer.registerSchema({
    name: "nav_msgs/msg/OccupancyGrid", encoding: "ros2msg", data: new TextEncoder().encode(DEFINITION),
  });
  const stringSchema = await writer.registerSchema({
    name: "std_msgs/msg/String", encoding: "ros2msg", data: new TextEncoder().encode("string data\n"),
  });
  const gridChannel = await writer.registerChannel({
    topic: a.topic, schemaId: gridSchema, messageEncoding: "cdr", metadata: new Map([["offered_qos_profiles", ""]]),
  });
  const chatter = await writer.registerChannel({
    topic: "/chatter", schemaId: stringSchema, messageEncoding: "cdr", metadata: new Map(),
  });
  const gridWriter = new MessageWriter(parse(DEFINITION, { ros2: true }));
  const stringWriter = new MessageWriter(parse("string data\n", { ros2: true }));
  const t0 = 1700000000n * NS;
  const events = [];
  for (let k = 1; k <= a.messages; k++) events.push([t0 + BigInt(k * 5) * NS, k]);
  for (let s = 0; s <= 5 * a.messages + 1; s += 2) events.push([t0 + BigInt(s) * NS + 7n, 0]);
  events.sort((x, y) => (x[0] < y[0] ? -1 : x[0] > y[0] ? 1 : 0));
  let sequence = 0, first = null, last = null, counts = { grid: 0, chatter: 0 };
  for (const [t, k] of events) {
    first ??= t; last = t;
    const stamp = { sec: Number(t / NS), nanosec: Number(t % NS) };
    let data, channelId;
    if (k === 0) {
      data = stringWriter.writeMessage({ data: "robot alive" });
      channelId = chatter; counts.chatter++;
    } else {
      const g = crop(map, k, a.messages);
      data = gridWriter.writeMessage({
        header: { stamp, frame_id: "map" },
        info: {
          map_load_time: stamp, resolution: g.resolution, width: g.width, height: g.height,
          origin: { position: { x: g.x, y: g.y, z: 0 },
                    orientation: { x: 0, y: 0, z: Math.sin(g.yaw / 2), w: Math.cos(g.yaw / 2) } },
        },
        data: g.cells,
      });
      channelId = gridChannel; counts.grid++;
    }
    await writer.addMessage({ channelId, sequence: sequence++, logTime: t, publishTime: t, data });
  }
  await writer.end();
  writable.close();
  // metadata.yaml as rosbag2 Jazzy writes it (version 9).
  const topic = (n, type, count) => `    - topic_metadata:
        name: ${n}
        type: ${type}
        serialization_format: cdr
        offered_qos_profiles: []
        type_description_hash: RIHS01_${"0".repeat(64)}
      message_count: ${count}`;
  fs.writeFileSync(path.join(a.out, "metadata.yaml"), `rosbag2_bagfile_information:
  version: 9
  storage_identifier: mcap
  duration:
    nanoseconds: ${last - first}
  starting_time:
    nanoseconds_since_epoch: ${first}
  message_count: ${counts.grid + counts.chatter}
  topics_with_message_count:
${topic("/chatter", "std_msgs/msg/String", counts.chatter)}
${topic(a.topic, "nav_msgs/msg/OccupancyGrid", counts.grid)}
  compression_format: ""
  compression_mode: ""
  relative_file_paths:
    - ${file}
  files:
    - path: ${file}
      starting_time:
        nanoseconds_since_epoch: ${first}
      duration:
        nanoseconds: ${last - first}
      message_count: ${counts.grid + counts.chatter}
  custom_data: ~
  ros_distro: jazzy
`);
}

await main();
