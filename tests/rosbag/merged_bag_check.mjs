// Checks a result set's merged_bag/ (rosbag/merged_bag.hpp) with readers fleetmerge did not
// write: npm's @mcap/core (the MCAP reference reader, indexed and streaming; @foxglove/crc for
// the data section CRC, which the readers do not check), @foxglove/rosmsg
// (ROS 2 .msg definitions) and @foxglove/rosmsg2-serialization (CDR), and `yaml` for
// metadata.yaml. The expected values come from the other files of the set, read here on their
// own: merged_<c>.yaml + merged_<c>.pgm (map_server semantics) and report.json (frames, poses).
//
//   node merged_bag_check.mjs RESULT_FOLDER      (npm ci in tests/rosbag first)
//
// Prints "merged_bag_check: OK ..." and exits 0, or prints what differs and exits 1.
import { McapIndexedReader, McapStreamReader } from "@mcap/core";
import { crc32 } from "@foxglove/crc";
import { parse as parseMsg } from "@foxglove/rosmsg";
import { MessageReader } from "@foxglove/rosmsg2-serialization";
import YAML from "yaml";
import { createHash } from "node:crypto";
import fs from "node:fs";
import path from "node:path";

const folder = process.argv[2];
const problems = [];
function check(ok, what) {
  if (!ok) problems.push(what);
  return ok;
}
const near = (a, b, tol) => Math.abs(a - b) <= tol;

// map_server's trinary reading of an 8-bit binary PGM (negate 0): cells bottom row first,
// 100 occupied, 0 free, -1 unknown.
function readMergedMap(yamlPath) {
  const meta = YAML.parse(fs.readFileSync(yamlPath, "utf8"));
  const data = fs.readFileSync(path.join(path.dirname(yamlPath), meta.image));
  const fields = [];
  let pos = 0;
  while (fields.length < 4) {
    while (/\s/.test(String.fromCharCode(data[pos]))) pos++;
    if (data[pos] === 0x23) {
      pos = data.indexOf(0x0a, pos) + 1;
      continue;
    }
    let end = pos;
    while (!/\s/.test(String.fromCharCode(data[end]))) end++;
    fields.push(data.subarray(pos, end).toString());
    pos = end;
  }
  if (fields[0] !== "P5" || fields[3] !== "255") throw new Error(yamlPath + ": expected an 8-bit P5");
  const width = Number(fields[1]), height = Number(fields[2]);
  const pixels = data.subarray(pos + 1);
  const cells = new Int8Array(width * height);
  for (let j = 0; j < height; j++) {
    for (let i = 0; i < width; i++) {
      const p = (255 - pixels[(height - 1 - j) * width + i]) / 255;
      cells[j * width + i] = p > meta.occupied_thresh ? 100 : p < meta.free_thresh ? 0 : -1;
    }
  }
  return { resolution: meta.resolution, origin: meta.origin, width, height, cells };
}

const yawOf = (q) => Math.atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y * q.y + q.z * q.z));
const angleDiff = (a, b) => Math.abs(Math.atan2(Math.sin(a - b), Math.cos(a - b)));

// REP 2011's RIHS01 type hash of a schema, computed from its definition text as rosidl computes
// it: the type and every type it uses (sorted by name), each field's type id, capacity, string
// capacity and nested type name (no default values, no constants), as JSON with Python's
// separators, hashed with SHA-256.
const kTypeIds = { int8: 2, uint8: 3, int16: 4, uint16: 5, int32: 6, uint32: 7, int64: 8,
  uint64: 9, float32: 10, float64: 11, char: 13, bool: 15, byte: 16, string: 17, wstring: 18 };
function rihs01(schemaName, definitions) {
  const full = (type) => (type.includes("/msg/") ? type : type.replace("/", "/msg/"));
  const byName = new Map(definitions.map((d, k) => [k === 0 ? schemaName : full(d.name), d]));
  const fieldJson = (f) => {
    let nested = "";
    if (f.type === "time") nested = "builtin_interfaces/msg/Time";  // @foxglove/rosmsg's names
    else if (f.type === "duration") nested = "builtin_interfaces/msg/Duration";
    else if (f.isComplex) nested = full(f.type);
    let id = nested ? 1 : kTypeIds[f.type];
    if (id === undefined) throw new Error(`${schemaName}: no type id for ${f.type}`);
    let capacity = 0;
    if (f.isArray && f.arrayLength !== undefined) [id, capacity] = [id + 48, f.arrayLength];
    else if (f.isArray && f.arrayUpperBound !== undefined) [id, capacity] = [id + 96, f.arrayUpperBound];
    else if (f.isArray) id += 144;
    return `{"name": ${JSON.stringify(f.name)}, "type": {"type_id": ${id}, "capacity": ${capacity}, ` +
           `"string_capacity": ${f.upperBound ?? 0}, "nested_type_name": ${JSON.stringify(nested)}}}`;
  };
  const used = new Set();
  const nestedOf = (name) => byName.get(name).definitions.filter((f) => !f.isConstant).map((f) =>
    f.type === "time" ? "builtin_interfaces/msg/Time" : f.type === "duration" ?
      "builtin_interfaces/msg/Duration" : f.isComplex ? full(f.type) : null).filter(Boolean);
  const walk = (name) => nestedOf(name).forEach((n) => !used.has(n) && (used.add(n), walk(n)));
  walk(schemaName);
  const describe = (name) => `{"type_name": ${JSON.stringify(name)}, "fields": [` +
    byName.get(name).definitions.filter((f) => !f.isConstant).map(fieldJson).join(", ") + "]}";
  const json = `{"type_description": ${describe(schemaName)}, "referenced_type_descriptions": [` +
    [...used].sort().map(describe).join(", ") + "]}";
  return "RIHS01_" + createHash("sha256").update(json).digest("hex");
}
// The hashes rosidl generates for these types (as in every ROS 2 Jazzy build's generated
// <type>__description.c): the schema text must describe the real types.
const kRosidlHashes = {
  "nav_msgs/msg/OccupancyGrid": "RIHS01_8d348150c12913a31ee0ec170fbf25089e4745d17035792a1ba94d6f0bc0cfc7",
  "tf2_msgs/msg/TFMessage": "RIHS01_e369d0f05a23ae52508854b66f6aa0437f3449d652e8cbf22d5abe85d020f087",
};

function checkQos(profiles, where) {
  check(Array.isArray(profiles) && profiles.length === 1, `${where}: one offered QoS profile`);
  const q = profiles[0] ?? {};
  check(q.history === "keep_last" && q.depth === 1, `${where}: history keep_last, depth 1`);
  check(q.reliability === "reliable", `${where}: reliability reliable`);
  check(q.durability === "transient_local", `${where}: durability transient_local`);
}

const report = JSON.parse(fs.readFileSync(path.join(folder, "report.json"), "utf8"));
const bagDir = path.join(folder, "merged_bag");
const metadataText = fs.readFileSync(path.join(bagDir, "metadata.yaml"), "utf8");
const info = YAML.parse(metadataText).rosbag2_bagfile_information;
// Nanoseconds since 1970 need 61 bits: read them as BigInt.
const startNs = YAML.parse(metadataText, { intAsBigInt: true }).rosbag2_bagfile_information
  .starting_time.nanoseconds_since_epoch;
check(info.version === 9, "metadata version 9");
check(info.storage_identifier === "mcap", "storage_identifier mcap");
check(JSON.stringify(info.relative_file_paths) === '["merged_bag_0.mcap"]', "relative_file_paths");
check(info.compression_format === "" && info.compression_mode === "", "no compression");
check(info.files?.length === 1 && info.files[0].path === "merged_bag_0.mcap", "files[0].path");

const bytes = new Uint8Array(fs.readFileSync(path.join(bagDir, "merged_bag_0.mcap")));
const readable = {
  size: async () => BigInt(bytes.length),
  read: async (offset, length) => bytes.subarray(Number(offset), Number(offset + length)),
};
const indexed = await McapIndexedReader.Initialize({ readable });
check(indexed.header.profile === "ros2", "MCAP profile ros2");
// DataEnd's CRC covers everything before it, magic and Header included (as @mcap/core writes it).
check(indexed.dataSectionCrc === crc32(bytes.subarray(0, Number(indexed.dataEndOffset))),
      "DataEnd's data section CRC");
const messages = [];
for await (const m of indexed.readMessages({ validateCrcs: true })) messages.push(m);
// The same file through the streaming reader (record by record, CRCs checked).
const stream = new McapStreamReader({ validateCrcs: true });
stream.append(bytes);
let streamed = 0;
for (let r; (r = stream.nextRecord());) if (r.type === "Message") streamed++;
check(stream.done(), "the streaming reader reads the whole file");
check(streamed === messages.length, `streamed ${streamed} messages, indexed ${messages.length}`);
check(indexed.statistics?.messageCount === BigInt(messages.length), "Statistics message count");

// Every topic of metadata.yaml is a channel with its messages; decode each message.
const decoded = new Map();  // topic -> [message]
for (const t of info.topics_with_message_count) {
  const meta = t.topic_metadata;
  const channel = [...indexed.channelsById.values()].find((c) => c.topic === meta.name);
  if (!check(channel, `${meta.name}: a channel in the MCAP`)) continue;
  const schema = indexed.schemasById.get(channel.schemaId);
  check(schema.name === meta.type, `${meta.name}: schema ${schema.name}, metadata ${meta.type}`);
  check(schema.encoding === "ros2msg" && channel.messageEncoding === "cdr", `${meta.name}: encodings`);
  check(meta.serialization_format === "cdr", `${meta.name}: serialization_format cdr`);
  checkQos(meta.offered_qos_profiles, `${meta.name} metadata.yaml`);
  checkQos(YAML.parse(channel.metadata.get("offered_qos_profiles")), `${meta.name} channel`);
  const definitions = parseMsg(new TextDecoder().decode(schema.data), { ros2: true });
  const hash = rihs01(schema.name, definitions);
  check(hash === kRosidlHashes[schema.name], `${meta.name}: schema hashes to ${hash}, rosidl's is ${kRosidlHashes[schema.name]}`);
  check(meta.type_description_hash === hash, `${meta.name}: type_description_hash ${meta.type_description_hash}, schema ${hash}`);
  check(channel.metadata.get("topic_type_hash") === hash, `${meta.name}: channel topic_type_hash`);
  const reader = new MessageReader(definitions);
  const mine = messages.filter((m) => m.channelId === channel.id);
  check(mine.length === t.message_count, `${meta.name}: ${mine.length} messages, metadata says ${t.message_count}`);
  for (const m of mine) {
    check(m.logTime === startNs, `${meta.name}: log time is starting_time`);
  }
  decoded.set(meta.name, mine.map((m) => reader.readMessage(m.data)));
}
check(info.message_count === messages.length, "metadata message_count");

// Maps: component c's merged map on /map (c = 0) or /merged_<c>/map, cell for cell.
let mapTopics = 0, cellsCompared = 0;
report.components.forEach((component, c) => {
  const topic = c === 0 ? "/map" : `/merged_${c}/map`;
  if (!component.merged_map) {
    check(!decoded.has(topic), `${topic}: no message for an unmerged component`);
    return;
  }
  mapTopics++;
  const msgs = decoded.get(topic);
  if (!check(msgs?.length === 1, `${topic}: one OccupancyGrid`)) return;
  const msg = msgs[0];
  const map = readMergedMap(path.join(folder, component.merged_map));
  check(msg.header.frame_id === component.frame, `${topic}: frame ${msg.header.frame_id}, report ${component.frame}`);
  check(msg.info.width === map.width && msg.info.height === map.height, `${topic}: size`);
  check(msg.info.resolution === Math.fround(map.resolution), `${topic}: resolution`);
  const o = msg.info.origin;
  check(near(o.position.x, map.origin[0], 1e-9) && near(o.position.y, map.origin[1], 1e-9) &&
        o.position.z === 0, `${topic}: origin position ${JSON.stringify(o.position)} vs ${map.origin}`);
  check(angleDiff(yawOf(o.orientation), map.origin[2]) < 1e-9, `${topic}: origin yaw`);
  check(msg.data.length === map.cells.length, `${topic}: ${msg.data.length} cells, PGM ${map.cells.length}`);
  let differ = 0;
  for (let k = 0; k < map.cells.length; k++) if (msg.data[k] !== map.cells[k]) differ++;
  check(differ === 0, `${topic}: ${differ} cells differ from ${component.merged_map}`);
  cellsCompared += map.cells.length;
});
const gridTopics = info.topics_with_message_count.filter((t) => t.topic_metadata.type === "nav_msgs/msg/OccupancyGrid");
check(gridTopics.length === mapTopics, `${gridTopics.length} map topics, ${mapTopics} merged maps`);

// /tf_static: one TFMessage, a transform per map of a merged component, as report.json's poses.
const tf = decoded.get("/tf_static");
let transforms = 0;
if (check(tf?.length === 1, "/tf_static: one TFMessage")) {
  const expected = report.maps.filter((m) => report.components[m.component].merged_map);
  check(tf[0].transforms.length === expected.length, `/tf_static: ${tf[0].transforms.length} transforms, ${expected.length} merged maps`);
  for (const m of expected) {
    const t = tf[0].transforms.find((x) => x.child_frame_id === m.frame);
    if (!check(t, `/tf_static: no transform to ${m.frame}`)) continue;
    transforms++;
    const where = `/tf_static ${m.frame}`;
    check(t.header.frame_id === report.components[m.component].frame, `${where}: parent frame`);
    const tr = t.transform.translation;
    check(near(tr.x, m.pose.x, 1e-9) && near(tr.y, m.pose.y, 1e-9) && tr.z === 0, `${where}: translation`);
    check(angleDiff(yawOf(t.transform.rotation), m.pose.yaw) < 1e-9, `${where}: yaw`);
  }
}

if (problems.length > 0) {
  console.error("merged_bag_check: " + folder + ":\n  " + problems.join("\n  "));
  process.exit(1);
}
console.log(`merged_bag_check: OK ${folder}: ${messages.length} messages, ${mapTopics} maps ` +
            `(${cellsCompared} cells), ${transforms} transforms`);
