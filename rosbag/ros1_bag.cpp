#include "rosbag/ros1_bag.hpp"

#include <algorithm>
#include <cstring>
#include <map>

#include "core/error.hpp"
#include "rosbag/binary_file.hpp"
#include "rosbag/byte_reader.hpp"
#include "rosbag/decompress.hpp"

namespace fleetmerge {
namespace {

constexpr char kMagic[] = "#ROSBAG V2.0\n";
constexpr std::size_t kMagicSize = sizeof(kMagic) - 1;
enum Op : std::uint8_t {
  kMessageData = 0x02,
  kBagHeader = 0x03,
  kIndexData = 0x04,
  kChunk = 0x05,
  kChunkInfo = 0x06,
  kConnection = 0x07,
};
// A record header or connection header longer than this is corrupt (real ones are < 10 kB;
// a message definition is the largest field).
constexpr std::uint32_t kMaxHeaderBytes = 16u << 20;

// "name=value" fields of a record header or a connection header.
using Fields = std::map<std::string, std::string>;

Fields ParseFields(std::string_view bytes, const std::string& context) {
  ByteReader r(bytes, context);
  Fields fields;
  while (!r.at_end()) {
    const std::uint32_t length = r.U32("header field length");
    const std::string_view field = r.Bytes(length, "header field");
    const std::size_t eq = field.find('=');
    if (eq == std::string_view::npos) {
      throw Error(context + ": header field without '=' (expected name=value)");
    }
    fields[std::string(field.substr(0, eq))] = std::string(field.substr(eq + 1));
  }
  return fields;
}

const std::string& Require(const Fields& fields, const char* name, const std::string& context) {
  const auto it = fields.find(name);
  if (it == fields.end()) throw Error(context + ": record header has no '" + name + "' field");
  return it->second;
}

template <typename T>
T FieldAs(const Fields& fields, const char* name, const std::string& context) {
  const std::string& value = Require(fields, name, context);
  if (value.size() != sizeof(T)) {
    throw Error(context + ": field '" + name + "' has " + std::to_string(value.size()) +
                " bytes, expected " + std::to_string(sizeof(T)));
  }
  T out;
  std::memcpy(&out, value.data(), sizeof(T));
  return out;
}

std::uint8_t OpOf(const Fields& fields, const std::string& context) {
  return FieldAs<std::uint8_t>(fields, "op", context);
}

std::int64_t TimeNs(std::uint64_t packed) {  // sec in the low 32 bits, nsec in the high
  return static_cast<std::int64_t>(packed & 0xffffffffu) * 1'000'000'000 +
         static_cast<std::int64_t>(packed >> 32);
}

// One record: its header fields, and where its data lies.
struct Record {
  Fields fields;
  std::uint8_t op = 0;
  std::uint64_t data_offset = 0, data_size = 0, end = 0;
};

Record ReadRecordAt(BinaryFile& file, std::uint64_t offset) {
  const std::string where = file.path().string() + ": record at byte " + std::to_string(offset);
  std::uint32_t header_size;
  std::memcpy(&header_size, file.Read(offset, 4, "record header length").data(), 4);
  if (header_size > kMaxHeaderBytes) {
    throw Error(where + ": header length " + std::to_string(header_size) + " is implausible " +
                "(corrupt bag)");
  }
  Record record;
  record.fields = ParseFields(file.Read(offset + 4, header_size, "record header"), where);
  record.op = OpOf(record.fields, where);
  std::uint32_t data_size;
  std::memcpy(&data_size, file.Read(offset + 4 + header_size, 4, "record data length").data(), 4);
  record.data_offset = offset + 8 + header_size;
  record.data_size = data_size;
  if (record.data_offset + data_size > file.size()) {
    throw Error(where + ": its data (" + std::to_string(data_size) + " bytes) runs past the end " +
                "of the file at byte " + std::to_string(file.size()) + " (truncated bag)");
  }
  record.end = record.data_offset + data_size;
  return record;
}

struct Connection {
  std::string topic, type;
};

Connection ReadConnection(const Fields& header, std::string_view data, const std::string& context) {
  Connection c;
  c.topic = Require(header, "topic", context);
  const Fields connection_header = ParseFields(data, context + " connection header");
  const auto type = connection_header.find("type");
  if (type == connection_header.end()) {
    throw Error(context + ": connection header of topic " + c.topic + " has no 'type'");
  }
  c.type = type->second;
  return c;
}

// The records of a decompressed chunk, in order; `visit(op, header, data)`.
template <typename Visit>
void ForEachInChunk(std::string_view chunk, const std::string& context, Visit visit) {
  ByteReader r(chunk, context);
  while (!r.at_end()) {
    const std::uint32_t header_size = r.U32("record header length");
    const Fields header = ParseFields(r.Bytes(header_size, "record header"), context);
    const std::uint32_t data_size = r.U32("record data length");
    const std::string_view data = r.Bytes(data_size, "record data");
    visit(OpOf(header, context), header, data);
  }
}

std::string ReadChunk(BinaryFile& file, const Record& record) {
  const std::string context =
      file.path().string() + ": chunk at byte " + std::to_string(record.data_offset);
  const std::string& compression = Require(record.fields, "compression", context);
  const std::uint32_t size = FieldAs<std::uint32_t>(record.fields, "size", context);
  std::string data = file.Read(record.data_offset, record.data_size, "chunk data");
  if (compression == "none") {
    if (data.size() != size) {
      throw Error(context + ": uncompressed chunk holds " + std::to_string(data.size()) +
                  " bytes, its header says " + std::to_string(size));
    }
    return data;
  }
  if (compression == "bz2") return DecompressBz2(data, size, context);
  if (compression == "lz4") return DecompressLz4Frame(data, size, context);
  throw Error(context + ": unknown chunk compression '" + compression +
              "' (expected none, bz2 or lz4)");
}

class Ros1Bag {
 public:
  explicit Ros1Bag(const std::filesystem::path& path) : file_(path) {
    const std::string magic =
        file_.Read(0, std::min<std::uint64_t>(kMagicSize, file_.size()), "format line");
    if (magic != kMagic) {
      if (magic.rfind("#ROSBAG V", 0) == 0) {
        throw Error(path.string() + ": ROS bag format " + magic.substr(9, 3) +
                    " is not supported (expected V2.0, written by ROS 1 since C Turtle)");
      }
      throw Error(path.string() + ": not a ROS 1 bag (expected it to begin with '#ROSBAG V2.0')");
    }
    const Record header = ReadRecordAt(file_, kMagicSize);
    const std::string context = path.string() + ": bag header";
    if (header.op != kBagHeader) throw Error(context + ": the first record is not a bag header");
    index_pos_ = FieldAs<std::uint64_t>(header.fields, "index_pos", context);
    first_record_ = header.end;
    if (index_pos_ != 0) ReadIndex();
  }

  std::vector<BagTopic> Topics() {
    if (index_pos_ == 0) ScanAll();
    std::map<std::string, BagTopic> topics;
    for (const auto& [id, c] : connections_) {
      BagTopic& t = topics[c.topic];
      t.name = c.topic;
      t.type = c.type;
      t.messages += counts_[id];
    }
    std::vector<BagTopic> out;
    for (auto& [name, t] : topics) out.push_back(std::move(t));
    return out;
  }

  std::optional<BagMessage> LastMessage(const std::string& topic) {
    if (index_pos_ == 0) {
      ScanAll(topic);
      return std::move(last_);
    }
    std::vector<std::uint32_t> ids;
    for (const auto& [id, c] : connections_) {
      if (c.topic == topic) ids.push_back(id);
    }
    // Chunks holding the topic, latest end time first; a chunk ending before the best message
    // found cannot hold a later one.
    std::vector<const ChunkInfo*> chunks;
    for (const ChunkInfo& info : chunks_) {
      for (std::uint32_t id : ids) {
        if (info.counts.count(id)) {
          chunks.push_back(&info);
          break;
        }
      }
    }
    std::sort(chunks.begin(), chunks.end(), [](const ChunkInfo* a, const ChunkInfo* b) {
      return a->end_ns != b->end_ns ? a->end_ns > b->end_ns : a->position > b->position;
    });
    std::optional<BagMessage> best;
    for (const ChunkInfo* info : chunks) {
      if (best && best->log_time_ns > info->end_ns) break;
      const Record record = ReadRecordAt(file_, info->position);
      if (record.op != kChunk) {
        throw Error(file_.path().string() + ": the index names a chunk at byte " +
                    std::to_string(info->position) + " where there is none (corrupt index)");
      }
      const std::string chunk = ReadChunk(file_, record);
      const std::string context =
          file_.path().string() + ": chunk at byte " + std::to_string(info->position);
      ForEachInChunk(chunk, context, [&](std::uint8_t op, const Fields& h, std::string_view d) {
        if (op != kMessageData) return;
        const auto conn = FieldAs<std::uint32_t>(h, "conn", context);
        if (std::find(ids.begin(), ids.end(), conn) == ids.end()) return;
        const std::int64_t t = TimeNs(FieldAs<std::uint64_t>(h, "time", context));
        if (!best || t > best->log_time_ns ||
            (t == best->log_time_ns && info->position >= best_position_)) {
          best = BagMessage{t, std::string(d)};
          best_position_ = info->position;
        }
      });
    }
    return best;
  }

 private:
  struct ChunkInfo {
    std::uint64_t position = 0;
    std::int64_t end_ns = 0;
    std::map<std::uint32_t, std::uint32_t> counts;
  };

  void ReadIndex() {
    const std::string context = file_.path().string() + ": index";
    if (index_pos_ < first_record_ || index_pos_ > file_.size()) {
      throw Error(context + ": index_pos " + std::to_string(index_pos_) + " is outside the file (" +
                  std::to_string(file_.size()) + " bytes; truncated bag)");
    }
    for (std::uint64_t offset = index_pos_; offset < file_.size();) {
      const Record record = ReadRecordAt(file_, offset);
      const std::string where =
          file_.path().string() + ": record at byte " + std::to_string(offset);
      if (record.op == kConnection) {
        const auto id = FieldAs<std::uint32_t>(record.fields, "conn", where);
        connections_[id] = ReadConnection(
            record.fields, file_.Read(record.data_offset, record.data_size, "connection"), where);
      } else if (record.op == kChunkInfo) {
        ChunkInfo info;
        info.position = FieldAs<std::uint64_t>(record.fields, "chunk_pos", where);
        info.end_ns = TimeNs(FieldAs<std::uint64_t>(record.fields, "end_time", where));
        const std::string data = file_.Read(record.data_offset, record.data_size, "chunk info");
        ByteReader r(data, where);
        while (!r.at_end()) {
          const std::uint32_t conn = r.U32("chunk info connection");
          const std::uint32_t count = r.U32("chunk info count");
          info.counts[conn] = count;
          counts_[conn] += count;
        }
        chunks_.push_back(std::move(info));
      }
      offset = record.end;
    }
  }

  // Every record in file order (unindexed bags): connections, and with `topic` its last message.
  void ScanAll(const std::string& topic = "") {
    connections_.clear();
    counts_.clear();
    std::uint64_t position = 0;
    const auto message = [&](std::int64_t t, std::uint32_t conn, std::string_view data) {
      ++counts_[conn];
      const auto c = connections_.find(conn);
      if (topic.empty() || c == connections_.end() || c->second.topic != topic) return;
      if (!last_ || t >= last_->log_time_ns) last_ = BagMessage{t, std::string(data)};
    };
    for (std::uint64_t offset = first_record_; offset < file_.size();) {
      const Record record = ReadRecordAt(file_, offset);
      position = offset;
      const std::string where =
          file_.path().string() + ": record at byte " + std::to_string(offset);
      if (record.op == kChunk) {
        const std::string chunk = ReadChunk(file_, record);
        const std::string context =
            file_.path().string() + ": chunk at byte " + std::to_string(position);
        ForEachInChunk(chunk, context, [&](std::uint8_t op, const Fields& h, std::string_view d) {
          if (op == kConnection) {
            connections_[FieldAs<std::uint32_t>(h, "conn", context)] =
                ReadConnection(h, d, context);
          } else if (op == kMessageData) {
            message(TimeNs(FieldAs<std::uint64_t>(h, "time", context)),
                    FieldAs<std::uint32_t>(h, "conn", context), d);
          }
        });
      } else if (record.op == kConnection) {
        connections_[FieldAs<std::uint32_t>(record.fields, "conn", where)] = ReadConnection(
            record.fields, file_.Read(record.data_offset, record.data_size, "connection"), where);
      } else if (record.op == kMessageData) {
        message(TimeNs(FieldAs<std::uint64_t>(record.fields, "time", where)),
                FieldAs<std::uint32_t>(record.fields, "conn", where),
                file_.Read(record.data_offset, record.data_size, "message"));
      }
      offset = record.end;
    }
  }

  BinaryFile file_;
  std::uint64_t index_pos_ = 0, first_record_ = 0;
  std::map<std::uint32_t, Connection> connections_;
  std::map<std::uint32_t, std::uint64_t> counts_;
  std::vector<ChunkInfo> chunks_;
  std::optional<BagMessage> last_;
  std::uint64_t best_position_ = 0;
};

}  // namespace

bool IsRos1BagPath(const std::filesystem::path& path) { return path.extension() == ".bag"; }

std::vector<BagTopic> Ros1BagTopics(const std::filesystem::path& bag) {
  return Ros1Bag(bag).Topics();
}

std::optional<BagMessage> Ros1BagLastMessage(const std::filesystem::path& bag,
                                             const std::string& topic) {
  return Ros1Bag(bag).LastMessage(topic);
}

}  // namespace fleetmerge
