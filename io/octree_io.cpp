#include "io/octree_io.hpp"

#include <octomap/OcTree.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>

#include "core/error.hpp"
#include "io/atomic_file.hpp"

namespace fleetmerge {
namespace fs = std::filesystem;
namespace {

// The two OctoMap file kinds and the first line each starts with (OctoMap's own magic lines).
enum class OctreeFormat { kBinary, kFull };
const std::string kBinaryMagic = "# Octomap OcTree binary file";
const std::string kFullMagic = "# Octomap OcTree file";

std::optional<OctreeFormat> FormatOf(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".bt") return OctreeFormat::kBinary;
  if (ext == ".ot") return OctreeFormat::kFull;
  return std::nullopt;
}

OctreeFormat RequireFormat(const fs::path& path) {
  const auto format = FormatOf(path);
  if (!format) {
    throw Error(path.string() + ": expected an octree file name ending in .bt or .ot");
  }
  return *format;
}

struct OctreeHeader {
  std::string id;
  std::size_t size = 0;
  double resolution_m = 0.0;
  std::size_t data_offset = 0;  // first byte after the "data" line
};

[[noreturn]] void Fail(const fs::path& path, const std::string& what) {
  throw Error(path.string() + ": " + what);
}

std::string Trimmed(std::string line) {
  while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
  return line;
}

// Reads the header lines as OctoMap writes them: the magic line, '#' comments, "id <type>",
// "size <nodes>", "res <metres>", then "data" and the tree's bytes.
OctreeHeader ParseHeader(const std::string& bytes, OctreeFormat format, const fs::path& path) {
  const std::string& magic = format == OctreeFormat::kBinary ? kBinaryMagic : kFullMagic;
  const std::string& other = format == OctreeFormat::kBinary ? kFullMagic : kBinaryMagic;
  std::istringstream in(bytes);
  std::string line;
  std::getline(in, line);
  if (Trimmed(line) != magic) {
    const std::string kind = format == OctreeFormat::kBinary ? "binary (.bt)" : "full (.ot)";
    if (Trimmed(line) == other) {
      Fail(path, "expected a " + kind + " OctoMap file, but it is the other kind; rename it to " +
                     (format == OctreeFormat::kBinary ? ".ot" : ".bt"));
    }
    Fail(path,
         "not an OctoMap octree: expected the first line '" + magic + "' of a " + kind + " file");
  }
  OctreeHeader header;
  bool have_size = false, have_res = false;
  int line_number = 1;
  while (std::getline(in, line)) {
    ++line_number;
    line = Trimmed(line);
    if (line.empty() || line[0] == '#') continue;
    std::istringstream words(line);
    std::string key;
    words >> key;
    const std::string where = "header line " + std::to_string(line_number) + ": ";
    if (key == "data") {
      if (!have_size || !have_res) Fail(path, where + "'data' before 'size' and 'res'");
      // "data" as the file's last line, without a newline, leaves the stream at its end.
      header.data_offset = in.eof() ? bytes.size() : static_cast<std::size_t>(in.tellg());
      return header;
    }
    if (key == "id") {
      words >> header.id;
    } else if (key == "size") {
      long long size = -1;
      if (!(words >> size) || size < 0) Fail(path, where + "expected 'size <node count>'");
      header.size = static_cast<std::size_t>(size);
      have_size = true;
    } else if (key == "res") {
      if (!(words >> header.resolution_m) || !std::isfinite(header.resolution_m) ||
          header.resolution_m <= 0.0) {
        Fail(path, where + "expected 'res <resolution in metres, > 0>'");
      }
      have_res = true;
    } else {
      Fail(path, where + "unexpected '" + key + "' (expected id, size, res or data)");
    }
  }
  Fail(path, "the header ends without a 'data' line (truncated or not an octree)");
}

void CheckHeader(const OctreeHeader& header, OctreeFormat format, const fs::path& path) {
  // Binary files from OctoMap before 1.4 carry no id; they are OcTrees.
  if (header.id.empty() && format == OctreeFormat::kFull) Fail(path, "the header has no 'id'");
  if (!header.id.empty() && header.id != "OcTree") {
    Fail(path, "is an octree of type '" + header.id +
                   "'; expected 'OcTree' (an occupancy octree without colour or time stamps)");
  }
  if (header.size == 0) Fail(path, "the octree is empty (size 0): nothing to merge");
}

// OctoMap's readers trust the data: they recurse as deep as its bits say and, past the end of a
// truncated stream, branch on a byte they never read (OcTreeBaseImpl::readNodesRecurs). So the
// encoding is walked here first, bounded by the tree depth and the bytes present, and OctoMap
// only ever reads a well-formed tree.
//   .bt: per inner node 2 bytes, 2 bits per child (00 unknown, 01 free leaf, 10 occupied leaf,
//        11 inner: its own 2 bytes follow, depth first) (OccupancyOcTreeBase::writeBinaryNode).
//   .ot: per node a float log-odds and a byte with one bit per existing child, depth first.
constexpr int kTreeDepth = 16;  // OcTree's fixed depth: leaves are at depth <= 16

class DataWalker {
 public:
  DataWalker(std::string_view data, const fs::path& path) : data_(data), path_(path) {}

  // Returns the number of nodes the data encodes (what OcTree::size() will say).
  std::size_t CountNodes(OctreeFormat format) {
    if (format == OctreeFormat::kBinary) {
      BinaryNode(0);
    } else {
      FullNode(0);
    }
    if (at_ != data_.size()) {
      Fail(path_, "the octree data is truncated or corrupt: " + std::to_string(data_.size() - at_) +
                      " bytes follow the end of the tree (at data byte " + std::to_string(at_) +
                      ")");
    }
    return nodes_;
  }

 private:
  unsigned char Byte() {
    if (at_ >= data_.size()) {
      Fail(path_, "the octree data is truncated or corrupt: it ends inside node " +
                      std::to_string(nodes_) + " (" + std::to_string(data_.size()) +
                      " data bytes)");
    }
    return static_cast<unsigned char>(data_[at_++]);
  }

  void TooDeep(int depth) {
    Fail(path_, "the octree data is truncated or corrupt: a node at depth " +
                    std::to_string(depth) + " has children (an OcTree is " +
                    std::to_string(kTreeDepth) + " levels deep)");
  }

  void BinaryNode(int depth) {
    ++nodes_;
    const unsigned bits = Byte() | (static_cast<unsigned>(Byte()) << 8);  // children 0-3, 4-7
    if (bits == 0 && depth > 0) {
      Fail(path_, "the octree data is truncated or corrupt: an inner node at depth " +
                      std::to_string(depth) + " has no children");
    }
    for (int child = 0; child < 8; ++child) {
      const unsigned code = (bits >> (2 * child)) & 3u;
      if (code == 1u || code == 2u) ++nodes_;  // a free or occupied leaf
      if (code == 3u) {
        if (depth + 1 >= kTreeDepth) TooDeep(depth + 1);
        BinaryNode(depth + 1);
      }
    }
  }

  void FullNode(int depth) {
    ++nodes_;
    float log_odds = 0.0f;
    char value[sizeof(float)];
    for (char& c : value) c = static_cast<char>(Byte());
    std::memcpy(&log_odds, value, sizeof(float));
    if (!std::isfinite(log_odds)) {
      Fail(path_, "the octree data is truncated or corrupt: node " + std::to_string(nodes_) +
                      " has a log-odds that is not a finite number");
    }
    const unsigned children = Byte();
    if (children != 0 && depth >= kTreeDepth) TooDeep(depth);
    for (int child = 0; child < 8; ++child) {
      if (children & (1u << child)) FullNode(depth + 1);
    }
  }

  std::string_view data_;
  const fs::path& path_;
  std::size_t at_ = 0;
  std::size_t nodes_ = 0;
};

std::string ReadBytes(const fs::path& path) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) Fail(path, "is a folder, expected an octree file");
  std::ifstream in(path, std::ios::binary);
  if (!in) Fail(path, "cannot open the octree file (missing or unreadable)");
  std::ostringstream bytes;
  bytes << in.rdbuf();
  if (bytes.str().empty()) Fail(path, "is empty (0 bytes), expected an OctoMap octree");
  return bytes.str();
}

}  // namespace

bool IsOctreePath(const fs::path& path) { return FormatOf(path).has_value(); }

void CheckOctreeFile(const fs::path& path) {
  const OctreeFormat format = RequireFormat(path);
  std::error_code ec;
  if (fs::is_directory(path, ec)) Fail(path, "is a folder, expected an octree file");
  std::ifstream in(path, std::ios::binary);
  if (!in) Fail(path, "cannot open the octree file (missing or unreadable)");
  std::string head(4096, '\0');  // the header is a few short lines
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  if (head.empty()) Fail(path, "is empty (0 bytes), expected an OctoMap octree");
  CheckHeader(ParseHeader(head, format, path), format, path);
}

std::unique_ptr<octomap::OcTree> LoadOctree(const fs::path& path) {
  const OctreeFormat format = RequireFormat(path);
  const std::string bytes = ReadBytes(path);
  const OctreeHeader header = ParseHeader(bytes, format, path);
  CheckHeader(header, format, path);
  const std::string_view data_bytes = std::string_view(bytes).substr(header.data_offset);
  const std::size_t nodes = DataWalker(data_bytes, path).CountNodes(format);
  if (nodes != header.size) {
    Fail(path, "the octree data is truncated or corrupt: the header says " +
                   std::to_string(header.size) + " nodes, the data holds " + std::to_string(nodes));
  }
  // Header and data are checked; OctoMap reads the data into a fresh tree of the file's
  // resolution.
  auto tree = std::make_unique<octomap::OcTree>(header.resolution_m);
  std::istringstream data(std::string(data_bytes), std::ios::binary);
  if (format == OctreeFormat::kBinary) {
    tree->readBinaryData(data);
  } else {
    tree->readData(data);
  }
  // Cannot fail after the walk above; kept as a guard should OctoMap's encoding change.
  if (data.fail() || tree->size() != header.size) {
    Fail(path, "the octree data is truncated or corrupt: the header says " +
                   std::to_string(header.size) + " nodes, " + std::to_string(tree->size()) +
                   " could be read");
  }
  return tree;
}

void SaveOctree(const octomap::OcTree& tree, const fs::path& path,
                const std::vector<fs::path>& protected_inputs, AtomicWrite mode) {
  const OctreeFormat format = RequireFormat(path);
  if (tree.size() == 0) Fail(path, "refusing to write an empty octree");
  CheckNotAnInput(path, protected_inputs);
  std::ostringstream bytes(std::ios::binary);
  if (format == OctreeFormat::kBinary) {
    // OctoMap's header, and its data written node by node from the root: writeBinaryConst()
    // and writeBinaryData() do the same but print "Writing N nodes to output stream..." on
    // stderr (Debian builds the library with its debug output), which `merge --quiet` must not.
    bytes << std::setprecision(17) << kBinaryMagic << "\n# (written by fleetmerge)\n#\nid "
          << tree.getTreeType() << "\nsize " << tree.size() << "\nres " << tree.getResolution()
          << "\ndata\n";
    tree.writeBinaryNode(bytes, tree.getRoot());  // the root exists: the tree is not empty
  } else {
    tree.write(bytes);
  }
  if (!bytes) Fail(path, "OctoMap could not serialise the octree");
  WriteFileAtomically(path, bytes.str(), protected_inputs, mode);
}

}  // namespace fleetmerge
