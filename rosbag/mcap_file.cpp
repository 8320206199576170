#include "rosbag/mcap_file.hpp"

#include <cstring>
#include <functional>
#include <map>

#include "core/error.hpp"
#include "rosbag/binary_file.hpp"
#include "rosbag/byte_reader.hpp"
#include "rosbag/decompress.hpp"
#include "rosbag/mcap_records.hpp"

namespace fleetmerge {
namespace {

std::string String(ByteReader& r, const char* what) {
  const std::uint32_t length = r.U32(what);
  return std::string(r.Bytes(length, what));
}

struct Channel {
  std::uint16_t schema_id = 0;
  std::string topic, encoding;
};

class McapReader {
 public:
  explicit McapReader(const std::filesystem::path& path) : file_(path) {
    const std::string magic =
        file_.Read(0, std::min<std::uint64_t>(mcap::kMagicSize, file_.size()), "magic");
    if (magic != std::string(mcap::kMagic, mcap::kMagicSize)) {
      throw Error(path.string() + ": not an MCAP file (expected the magic bytes \\x89MCAP0)");
    }
  }

  // Visits every channel and message record in the data section, in file order.
  void Scan(const std::function<void(const Channel&, std::uint16_t, std::int64_t,
                                     std::string_view)>& on_message) {
    for (std::uint64_t offset = mcap::kMagicSize; offset < file_.size();) {
      const std::string head = file_.Read(offset, 9, "record opcode and length");
      const auto op = static_cast<std::uint8_t>(head[0]);
      std::uint64_t length;
      std::memcpy(&length, head.data() + 1, 8);
      const std::string where =
          file_.path().string() + ": record at byte " + std::to_string(offset);
      if (length > file_.size() - offset - 9) {
        throw Error(where + ": its length " + std::to_string(length) +
                    " runs past the end of the file (truncated or corrupt MCAP)");
      }
      if (op == mcap::kFooter || op == mcap::kDataEnd) return;
      if (op == mcap::kSchema || op == mcap::kChannel || op == mcap::kMessage ||
          op == mcap::kChunk) {
        const std::string body = file_.Read(offset + 9, length, "record");
        if (op == mcap::kChunk) {
          Chunk(body, where, on_message);
        } else {
          Record(op, body, where, on_message);
        }
      }
      offset += 9 + length;
    }
  }

  const std::map<std::uint16_t, std::string>& schemas() const { return schemas_; }
  const std::map<std::uint16_t, Channel>& channels() const { return channels_; }

 private:
  using OnMessage =
      std::function<void(const Channel&, std::uint16_t, std::int64_t, std::string_view)>;

  void Record(std::uint8_t op, std::string_view body, const std::string& where,
              const OnMessage& on_message) {
    ByteReader r(body, where);
    if (op == mcap::kSchema) {
      const std::uint16_t id = r.U16("schema id");
      schemas_[id] = String(r, "schema name");
    } else if (op == mcap::kChannel) {
      const std::uint16_t id = r.U16("channel id");
      Channel c;
      c.schema_id = r.U16("channel schema id");
      c.topic = String(r, "channel topic");
      c.encoding = String(r, "channel message encoding");
      channels_[id] = c;
    } else if (op == mcap::kMessage) {
      const std::uint16_t channel = r.U16("message channel id");
      r.U32("message sequence");
      const auto log_time = static_cast<std::int64_t>(r.U64("message log time"));
      r.U64("message publish time");
      const auto it = channels_.find(channel);
      if (it == channels_.end()) {
        throw Error(where + ": message on channel " + std::to_string(channel) +
                    ", which no channel record before it defines");
      }
      on_message(it->second, channel, log_time, body.substr(r.offset()));
    }
  }

  void Chunk(std::string_view body, const std::string& where, const OnMessage& on_message) {
    ByteReader r(body, where + " (chunk)");
    r.U64("chunk start time");
    r.U64("chunk end time");
    const std::uint64_t size = r.U64("chunk uncompressed size");
    r.U32("chunk uncompressed crc");
    const std::string compression = String(r, "chunk compression");
    const std::uint64_t length = r.U64("chunk records length");
    const std::string_view records = r.Bytes(length, "chunk records");
    const std::string context = where + " (chunk, " +
                                (compression.empty() ? std::string("uncompressed") : compression) +
                                ")";
    if (size > kMaxChunkBytes) {
      throw Error(context + ": announces " + std::to_string(size) + " bytes uncompressed, more " +
                  "than the limit of " + std::to_string(kMaxChunkBytes));
    }
    std::string data;
    if (compression.empty()) {
      if (records.size() != size) {
        throw Error(context + ": holds " + std::to_string(records.size()) +
                    " bytes, its header says " + std::to_string(size));
      }
      data = std::string(records);
    } else if (compression == "zstd") {
      data = DecompressZstd(records, size, context);
    } else if (compression == "lz4") {
      data = DecompressLz4Frame(records, size, context);
    } else {
      throw Error(context + ": unknown chunk compression '" + compression +
                  "' (expected none, zstd or lz4)");
    }
    ByteReader inner(data, context);
    while (!inner.at_end()) {
      const std::size_t at = inner.offset();
      const std::uint8_t op = inner.U8("record opcode");
      const std::uint64_t record_length = inner.U64("record length");
      const std::string_view record = inner.Bytes(record_length, "record");
      Record(op, record, context + ", record at offset " + std::to_string(at), on_message);
    }
  }

  BinaryFile file_;
  std::map<std::uint16_t, std::string> schemas_;
  std::map<std::uint16_t, Channel> channels_;
};

}  // namespace

std::vector<BagTopic> McapTopics(const std::filesystem::path& file) {
  McapReader reader(file);
  std::map<std::uint16_t, std::uint64_t> counts;
  reader.Scan(
      [&](const Channel&, std::uint16_t id, std::int64_t, std::string_view) { ++counts[id]; });
  std::map<std::string, BagTopic> topics;
  for (const auto& [id, c] : reader.channels()) {
    BagTopic& t = topics[c.topic];
    t.name = c.topic;
    const auto schema = reader.schemas().find(c.schema_id);
    t.type = schema != reader.schemas().end() ? schema->second : "(no schema)";
    t.messages += counts[id];
  }
  std::vector<BagTopic> out;
  for (auto& [name, t] : topics) out.push_back(std::move(t));
  return out;
}

std::optional<BagMessage> McapLastMessage(const std::filesystem::path& file,
                                          const std::string& topic) {
  McapReader reader(file);
  std::optional<BagMessage> last;
  reader.Scan([&](const Channel& c, std::uint16_t, std::int64_t t, std::string_view data) {
    if (c.topic != topic) return;
    if (c.encoding != "cdr") {
      throw Error(file.string() + ": topic " + topic + " has message encoding '" + c.encoding +
                  "', expected 'cdr' (ROS 2)");
    }
    if (!last || t >= last->log_time_ns) last = BagMessage{t, std::string(data)};
  });
  return last;
}

}  // namespace fleetmerge
