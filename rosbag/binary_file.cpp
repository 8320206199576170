#include "rosbag/binary_file.hpp"

#include "core/error.hpp"

namespace fleetmerge {

BinaryFile::BinaryFile(const std::filesystem::path& path) : path_(path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw Error(path.string() + ": is a folder");
  in_.open(path, std::ios::binary);
  if (!in_) throw Error(path.string() + ": cannot open");
  in_.seekg(0, std::ios::end);
  size_ = static_cast<std::uint64_t>(in_.tellg());
}

std::string BinaryFile::Read(std::uint64_t offset, std::uint64_t n, const char* what) {
  if (offset > size_ || n > size_ - offset) {
    throw Error(path_.string() + ": " + what + " at byte " + std::to_string(offset) + " needs " +
                std::to_string(n) + " bytes, the file ends at byte " + std::to_string(size_) +
                " (truncated or corrupt)");
  }
  std::string out(n, '\0');
  in_.clear();
  in_.seekg(static_cast<std::streamoff>(offset));
  in_.read(out.data(), static_cast<std::streamsize>(n));
  if (static_cast<std::uint64_t>(in_.gcount()) != n) {
    throw Error(path_.string() + ": cannot read " + what + " at byte " + std::to_string(offset));
  }
  return out;
}

}  // namespace fleetmerge
