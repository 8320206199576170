#include "rosbag/ros2_bag.hpp"

#include <yaml-cpp/yaml.h>

#include <fstream>
#include <map>
#include <sstream>

#include "core/error.hpp"
#include "rosbag/decompress.hpp"
#include "rosbag/mcap_file.hpp"
#include "rosbag/sqlite_bag.hpp"

namespace fleetmerge {
namespace fs = std::filesystem;
namespace {

bool IsStorageFile(const fs::path& path) {
  return path.extension() == ".db3" || path.extension() == ".mcap";
}

// metadata.yaml errors in the house format of io/yaml_errors.hpp ("<file>: line L: key 'k':
// what"), formatted here because rosbag/ sits below io/ (io/bag_maps.cpp reads maps from bags).
class MetadataErrors {
 public:
  explicit MetadataErrors(const fs::path& path) : path_(path.string()) {}
  [[noreturn]] void Fail(const std::string& what) const { throw Error(path_ + ": " + what); }
  [[noreturn]] void Fail(const std::string& key, int line, const std::string& what) const {
    Fail("line " + std::to_string(line) + ": key '" + key + "': " + what);
  }

 private:
  std::string path_;
};

// rosbag2 writes a few kilobytes; anything this large is the wrong file.
constexpr std::uintmax_t kMaxMetadataBytes = 16u << 20;

YAML::Node ReadMetadata(const fs::path& path, const MetadataErrors& errors) {
  std::error_code ec;
  const std::uintmax_t bytes = fs::file_size(path, ec);
  if (!ec && bytes > kMaxMetadataBytes) {
    errors.Fail("is " + std::to_string(bytes) + " bytes, too large for a ROS 2 bag metadata " +
                "file (at most " + std::to_string(kMaxMetadataBytes) + "): is it the right file?");
  }
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in) errors.Fail("cannot read ROS 2 bag metadata");
  try {
    return YAML::Load(text.str());
  } catch (const YAML::Exception& e) {
    if (e.mark.is_null()) errors.Fail("malformed YAML: " + e.msg);
    errors.Fail("line " + std::to_string(e.mark.line + 1) + ", column " +
                std::to_string(e.mark.column + 1) + ": malformed YAML: " + e.msg);
  }
}

std::string ScalarOr(const YAML::Node& node, const std::string& fallback) {
  return node && node.IsScalar() ? node.Scalar() : fallback;
}

Ros2Bag ReadFolder(const fs::path& folder) {
  const fs::path metadata = folder / "metadata.yaml";
  std::error_code ec;
  if (!fs::is_regular_file(metadata, ec)) {
    std::string found;  // a file the user may have meant
    for (const auto& entry : fs::directory_iterator(folder, ec)) {
      if (IsStorageFile(entry.path())) found = entry.path().filename().string();
      if (found.empty() && entry.path().extension() == ".yaml") {
        found = entry.path().filename().string();
      }
    }
    throw Error(
        folder.string() + ": is a folder but not a ROS 2 bag (expected metadata.yaml " +
        "beside .db3 or .mcap files)" +
        (found.empty() ? std::string() : "; it holds " + found + ": give that file instead"));
  }
  const MetadataErrors errors(metadata);
  const YAML::Node root = ReadMetadata(metadata, errors);
  const YAML::Node info = root.IsMap() ? root["rosbag2_bagfile_information"] : YAML::Node();
  if (!info || !info.IsMap()) {
    errors.Fail("expected a mapping 'rosbag2_bagfile_information' (rosbag2's metadata.yaml)");
  }
  const std::string storage = ScalarOr(info["storage_identifier"], "");
  if (storage != "sqlite3" && storage != "mcap") {
    errors.Fail("storage_identifier", info["storage_identifier"].Mark().line + 1,
                "expected sqlite3 or mcap, got '" + storage + "'");
  }
  const YAML::Node paths = info["relative_file_paths"];
  if (!paths || !paths.IsSequence() || paths.size() == 0) {
    errors.Fail("expected 'relative_file_paths': a non-empty list of the bag's storage files");
  }
  Ros2Bag bag;
  bag.path = folder;
  const std::string compression_mode = ScalarOr(info["compression_mode"], "");
  const std::string compression_format = ScalarOr(info["compression_format"], "");
  if (!compression_mode.empty() && compression_mode != "NONE") {
    if (compression_format != "zstd") {
      errors.Fail("compression_format", info["compression_format"].Mark().line + 1,
                  "expected zstd (the only rosbag2 compressor), got '" + compression_format + "'");
    }
    if (compression_mode == "FILE") {
      errors.Fail("compression_mode", info["compression_mode"].Mark().line + 1,
                  "FILE compression (whole .zstd storage files) is not read; run `ros2 bag "
                  "decompress` first, or record with --compression-mode message");
    }
    if (compression_mode != "MESSAGE") {
      errors.Fail("compression_mode", info["compression_mode"].Mark().line + 1,
                  "expected NONE, FILE or MESSAGE, got '" + compression_mode + "'");
    }
    bag.message_zstd = true;
  }
  for (const YAML::Node& p : paths) {
    const fs::path file = folder / ScalarOr(p, "");
    if (!p.IsScalar() || !fs::is_regular_file(file, ec)) {
      errors.Fail("relative_file_paths", p.Mark().line + 1,
                  "storage file '" + file.string() + "' does not exist");
    }
    if (file.extension() != (storage == "mcap" ? ".mcap" : ".db3")) {
      errors.Fail("relative_file_paths", p.Mark().line + 1,
                  "'" + file.filename().string() + "' does not end in " +
                      (storage == "mcap" ? ".mcap" : ".db3") + " (storage " + storage + ")");
    }
    bag.files.push_back(file);
  }
  return bag;
}

std::vector<BagTopic> FileTopics(const fs::path& file) {
  return file.extension() == ".mcap" ? McapTopics(file) : SqliteBagTopics(file);
}

std::optional<BagMessage> FileLastMessage(const fs::path& file, const std::string& topic) {
  return file.extension() == ".mcap" ? McapLastMessage(file, topic)
                                     : SqliteBagLastMessage(file, topic);
}

}  // namespace

bool IsRos2BagPath(const fs::path& path) {
  std::error_code ec;
  return IsStorageFile(path) || fs::is_directory(path, ec);
}

Ros2Bag OpenRos2Bag(const fs::path& path) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) return ReadFolder(path);
  if (!fs::is_regular_file(path, ec)) throw Error(path.string() + ": no such file or folder");
  Ros2Bag bag;
  bag.path = path;
  bag.files = {path};
  return bag;
}

std::vector<BagTopic> Ros2BagTopics(const Ros2Bag& bag) {
  std::map<std::string, BagTopic> topics;
  for (const fs::path& file : bag.files) {
    for (BagTopic& t : FileTopics(file)) {
      BagTopic& merged = topics[t.name];
      merged.name = t.name;
      merged.type = t.type;
      merged.messages += t.messages;
    }
  }
  std::vector<BagTopic> out;
  for (auto& [name, t] : topics) out.push_back(std::move(t));
  return out;
}

std::optional<BagMessage> Ros2BagLastMessage(const Ros2Bag& bag, const std::string& topic) {
  std::optional<BagMessage> last;
  fs::path last_file;
  for (const fs::path& file : bag.files) {
    std::optional<BagMessage> m = FileLastMessage(file, topic);
    if (m && (!last || m->log_time_ns >= last->log_time_ns)) {
      last = std::move(m);
      last_file = file;
    }
  }
  if (last && bag.message_zstd) {
    const std::string context = last_file.string() + ": message on " + topic;
    last->data = DecompressZstdFrame(last->data, context);
  }
  return last;
}

}  // namespace fleetmerge
