#include "rosbag/mcap_writer.hpp"

#include <zlib.h>

#include <algorithm>
#include <limits>
#include <utility>

#include "core/error.hpp"
#include "rosbag/byte_writer.hpp"
#include "rosbag/mcap_records.hpp"

namespace fleetmerge {
namespace {

// A record's opcode and uint64 content length; its content follows.
void PutRecordHeader(ByteWriter& out, mcap::Op opcode, std::uint64_t content_bytes) {
  out.Put(static_cast<std::uint8_t>(opcode));
  out.Put(content_bytes);
}

// One record: opcode, uint64 content length, content.
void PutRecord(ByteWriter& out, mcap::Op opcode, const std::string& content) {
  PutRecordHeader(out, opcode, content.size());
  out.Bytes(content);
}

constexpr std::uint64_t kRecordHeaderBytes = 1 + 8;
constexpr std::uint64_t kMessageFieldsBytes = 2 + 4 + 8 + 8;  // channel, sequence, two times

// Map<string, string>: a uint32 byte length, then key/value strings, keys sorted.
std::string StringMap(const std::map<std::string, std::string>& entries) {
  ByteWriter body;
  for (const auto& [key, value] : entries) {
    body.Prefixed(key);
    body.Prefixed(value);
  }
  ByteWriter out;
  out.Prefixed(body.bytes());
  return out.bytes();
}

}  // namespace

// zlib's crc32 is the same CRC (MCAP's spec names it) and ~10x faster than a byte table: the
// merged bag's two checksums ran over the whole map twice.
std::uint32_t Crc32(const std::string& bytes, std::size_t begin, std::size_t end) {
  const auto* data = reinterpret_cast<const Bytef*>(bytes.data() + begin);
  return static_cast<std::uint32_t>(crc32_z(crc32_z(0L, Z_NULL, 0), data, end - begin));
}

McapWriter::McapWriter(std::string profile, std::string library)
    : profile_(std::move(profile)), library_(std::move(library)) {}

std::uint16_t McapWriter::AddSchema(const std::string& name, const std::string& encoding,
                                    const std::string& data) {
  const auto id = static_cast<std::uint16_t>(schemas_.size() + 1);
  schemas_.push_back({id, name, encoding, data});
  return id;
}

std::uint16_t McapWriter::AddChannel(std::uint16_t schema_id, const std::string& topic,
                                     const std::string& message_encoding,
                                     const std::map<std::string, std::string>& metadata) {
  if (schema_id == 0 || schema_id > schemas_.size()) {
    throw Error("MCAP writer: channel " + topic + " names schema " + std::to_string(schema_id) +
                ", which was not added");
  }
  const auto id = static_cast<std::uint16_t>(channels_.size() + 1);
  channels_.push_back({id, schema_id, topic, message_encoding, metadata});
  return id;
}

void McapWriter::AddMessage(std::uint16_t channel_id, std::uint64_t log_time_ns,
                            std::uint64_t publish_time_ns, std::string data) {
  if (channel_id == 0 || channel_id > channels_.size()) {
    throw Error("MCAP writer: a message names channel " + std::to_string(channel_id) +
                ", which was not added");
  }
  const auto sequence = static_cast<std::uint32_t>(
      std::count_if(messages_.begin(), messages_.end(),
                    [&](const Message& m) { return m.channel_id == channel_id; }));
  messages_.push_back({channel_id, sequence, log_time_ns, publish_time_ns, std::move(data)});
}

void McapWriter::AddMetadata(const std::string& name,
                             const std::map<std::string, std::string>& metadata) {
  metadata_.push_back({name, metadata});
}

std::string McapWriter::Finish() const {
  // Record contents, each built once and written both in the chunk and in the summary.
  std::vector<std::string> schema_records, channel_records;
  for (const Schema& s : schemas_) {
    ByteWriter r;
    r.Put(s.id);
    r.Prefixed(s.name);
    r.Prefixed(s.encoding);
    r.Prefixed(s.data);
    schema_records.push_back(r.bytes());
  }
  for (const Channel& c : channels_) {
    ByteWriter r;
    r.Put(c.id);
    r.Put(c.schema_id);
    r.Prefixed(c.topic);
    r.Prefixed(c.message_encoding);
    r.Bytes(StringMap(c.metadata));
    channel_records.push_back(r.bytes());
  }

  // The chunk's records; each message's offset inside them goes to its channel's MessageIndex.
  // Schema and channel records, in the chunk and again in the summary.
  std::uint64_t definition_bytes = 0;
  for (const auto* records : {&schema_records, &channel_records}) {
    for (const std::string& r : *records) definition_bytes += kRecordHeaderBytes + r.size();
  }
  ByteWriter chunk_records;
  std::uint64_t chunk_bytes = definition_bytes;
  for (const Message& m : messages_) {
    chunk_bytes += kRecordHeaderBytes + kMessageFieldsBytes + m.data.size();
  }
  chunk_records.Reserve(chunk_bytes);
  for (const std::string& r : schema_records) PutRecord(chunk_records, mcap::kSchema, r);
  for (const std::string& r : channel_records) PutRecord(chunk_records, mcap::kChannel, r);
  std::map<std::uint16_t, std::vector<std::pair<std::uint64_t, std::uint64_t>>> index;
  std::map<std::uint16_t, std::uint64_t> counts;
  std::uint64_t start_ns = std::numeric_limits<std::uint64_t>::max(), end_ns = 0;
  for (const Message& m : messages_) {
    index[m.channel_id].push_back({m.log_time_ns, chunk_records.size()});
    ++counts[m.channel_id];
    start_ns = std::min(start_ns, m.log_time_ns);
    end_ns = std::max(end_ns, m.log_time_ns);
    PutRecordHeader(chunk_records, mcap::kMessage, kMessageFieldsBytes + m.data.size());
    chunk_records.Put(m.channel_id);
    chunk_records.Put(m.sequence);
    chunk_records.Put(m.log_time_ns);
    chunk_records.Put(m.publish_time_ns);
    chunk_records.Bytes(m.data);
  }
  if (messages_.empty()) start_ns = 0;

  ByteWriter file;
  // The chunk and everything around it: the definitions again, the metadata, and the indexes
  // and summary records, which are small.
  std::uint64_t around_bytes = definition_bytes + 4096;
  for (const Metadata& m : metadata_) {
    around_bytes += m.name.size() + 64;
    for (const auto& [key, value] : m.entries) around_bytes += key.size() + value.size() + 8;
  }
  file.Reserve(chunk_records.size() + around_bytes);
  file.Bytes(std::string_view(mcap::kMagic, mcap::kMagicSize));
  {
    ByteWriter r;
    r.Prefixed(profile_);
    r.Prefixed(library_);
    PutRecord(file, mcap::kHeader, r.bytes());
  }
  const std::uint64_t chunk_start = file.size();
  {
    const std::string& records = chunk_records.bytes();
    PutRecordHeader(file, mcap::kChunk, 8 + 8 + 8 + 4 + 4 + 8 + records.size());
    file.Put(start_ns);
    file.Put(end_ns);
    file.Put(static_cast<std::uint64_t>(records.size()));
    file.Put(Crc32(records, 0, records.size()));
    file.Prefixed("");  // compression: none
    file.Put(static_cast<std::uint64_t>(records.size()));
    file.Bytes(records);
  }
  const std::uint64_t chunk_length = file.size() - chunk_start;
  std::map<std::uint16_t, std::uint64_t> index_offsets;
  const std::uint64_t indexes_start = file.size();
  for (const auto& [channel_id, entries] : index) {
    index_offsets[channel_id] = file.size();
    ByteWriter body;
    for (const auto& [time_ns, offset] : entries) {
      body.Put(time_ns);
      body.Put(offset);
    }
    ByteWriter r;
    r.Put(channel_id);
    r.Prefixed(body.bytes());
    PutRecord(file, mcap::kMessageIndex, r.bytes());
  }
  const std::uint64_t indexes_length = file.size() - indexes_start;
  struct MetadataPlace {
    std::uint64_t offset, length;
    std::string name;
  };
  std::vector<MetadataPlace> metadata_places;
  for (const Metadata& m : metadata_) {
    const std::uint64_t offset = file.size();
    ByteWriter r;
    r.Prefixed(m.name);
    r.Bytes(StringMap(m.entries));
    PutRecord(file, mcap::kMetadata, r.bytes());
    metadata_places.push_back({offset, file.size() - offset, m.name});
  }
  {
    ByteWriter r;
    r.Put(Crc32(file.bytes(), 0, file.size()));
    PutRecord(file, mcap::kDataEnd, r.bytes());
  }

  // Summary section: each group's place goes to a SummaryOffset record.
  const std::uint64_t summary_start = file.size();
  std::vector<std::tuple<mcap::Op, std::uint64_t, std::uint64_t>> groups;
  const auto group = [&](mcap::Op opcode, const std::vector<std::string>& records) {
    if (records.empty()) return;
    const std::uint64_t start = file.size();
    for (const std::string& r : records) PutRecord(file, opcode, r);
    groups.emplace_back(opcode, start, file.size() - start);
  };
  group(mcap::kSchema, schema_records);
  group(mcap::kChannel, channel_records);
  {
    ByteWriter r;
    r.Put(static_cast<std::uint64_t>(messages_.size()));
    r.Put(static_cast<std::uint16_t>(schemas_.size()));
    r.Put(static_cast<std::uint32_t>(channels_.size()));
    r.Put(static_cast<std::uint32_t>(0));  // attachments
    r.Put(static_cast<std::uint32_t>(metadata_.size()));
    r.Put(static_cast<std::uint32_t>(1));  // chunks
    r.Put(start_ns);
    r.Put(end_ns);
    ByteWriter map;
    for (const auto& [channel_id, count] : counts) {
      map.Put(channel_id);
      map.Put(count);
    }
    r.Prefixed(map.bytes());
    group(mcap::kStatistics, {r.bytes()});
  }
  {
    ByteWriter r;
    r.Put(start_ns);
    r.Put(end_ns);
    r.Put(chunk_start);
    r.Put(chunk_length);
    ByteWriter map;
    for (const auto& [channel_id, offset] : index_offsets) {
      map.Put(channel_id);
      map.Put(offset);
    }
    r.Prefixed(map.bytes());
    r.Put(indexes_length);
    r.Prefixed("");
    r.Put(static_cast<std::uint64_t>(chunk_records.size()));  // compressed size: stored as is
    r.Put(static_cast<std::uint64_t>(chunk_records.size()));
    group(mcap::kChunkIndex, {r.bytes()});
  }
  {
    std::vector<std::string> records;
    for (const MetadataPlace& place : metadata_places) {
      ByteWriter r;
      r.Put(place.offset);
      r.Put(place.length);
      r.Prefixed(place.name);
      records.push_back(r.bytes());
    }
    group(mcap::kMetadataIndex, records);
  }
  const std::uint64_t summary_offset_start = file.size();
  for (const auto& [opcode, start, length] : groups) {
    ByteWriter r;
    r.Put(static_cast<std::uint8_t>(opcode));
    r.Put(start);
    r.Put(length);
    PutRecord(file, mcap::kSummaryOffset, r.bytes());
  }
  // Footer: its CRC covers the summary section and the footer up to the CRC field.
  const std::size_t footer_start = file.size();
  file.Put(static_cast<std::uint8_t>(mcap::kFooter));
  file.Put(static_cast<std::uint64_t>(8 + 8 + 4));
  file.Put(summary_start);
  file.Put(summary_offset_start);
  file.Put(Crc32(file.bytes(), summary_start, footer_start + 1 + 8 + 8 + 8));
  file.Bytes(std::string_view(mcap::kMagic, mcap::kMagicSize));
  return file.Release();
}

}  // namespace fleetmerge
