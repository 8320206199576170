// Writes an MCAP file (https://mcap.dev/spec) in memory: the writing side of rosbag/mcap_file.hpp,
// for small bags made at once (fleetmerge's merged_bag/, rosbag/merged_bag.hpp).
//
// Layout, as rosbag2_storage_mcap's default writer lays its files out (chunked, uncompressed, with
// a summary) so that `ros2 bag`, Foxglove and indexed readers (@mcap/core's McapIndexedReader,
// which reads messages only through chunk indexes) all read it:
//   magic, Header, one Chunk (compression "") holding every Schema, Channel and Message record,
//   a MessageIndex per channel with messages, the Metadata records, DataEnd (data section CRC),
//   summary: Schemas, Channels, Statistics, ChunkIndex, MetadataIndex; a SummaryOffset per group;
//   Footer (summary CRC), magic.
// CRCs are CRC-32 (ISO-HDLC, as zlib), computed everywhere the format has one.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace fleetmerge {

class McapWriter {
 public:
  // `profile`: "ros2" for ROS 2 bags; `library`: who wrote the file.
  McapWriter(std::string profile, std::string library);

  // Ids start at 1 (0 means "no schema" in a Channel record).
  std::uint16_t AddSchema(const std::string& name, const std::string& encoding,
                          const std::string& data);
  std::uint16_t AddChannel(std::uint16_t schema_id, const std::string& topic,
                           const std::string& message_encoding,
                           const std::map<std::string, std::string>& metadata);
  // `data` is kept until Finish (moved in: a merged map's message is its whole grid).
  void AddMessage(std::uint16_t channel_id, std::uint64_t log_time_ns,
                  std::uint64_t publish_time_ns, std::string data);
  void AddMetadata(const std::string& name, const std::map<std::string, std::string>& metadata);

  // The whole file. Each message's bytes are copied twice, into the chunk and the chunk into the
  // file, each buffer sized once.
  std::string Finish() const;

 private:
  struct Schema {
    std::uint16_t id;
    std::string name, encoding, data;
  };
  struct Channel {
    std::uint16_t id, schema_id;
    std::string topic, message_encoding;
    std::map<std::string, std::string> metadata;
  };
  struct Message {
    std::uint16_t channel_id;
    std::uint32_t sequence;
    std::uint64_t log_time_ns, publish_time_ns;
    std::string data;
  };
  struct Metadata {
    std::string name;
    std::map<std::string, std::string> entries;
  };
  std::string profile_, library_;
  std::vector<Schema> schemas_;
  std::vector<Channel> channels_;
  std::vector<Message> messages_;
  std::vector<Metadata> metadata_;
};

// CRC-32 as zlib's crc32 (polynomial 0xEDB88320, initial and final XOR 0xFFFFFFFF).
std::uint32_t Crc32(const std::string& bytes, std::size_t begin, std::size_t end);

}  // namespace fleetmerge
