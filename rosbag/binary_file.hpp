// Random reads from a file that may be larger than memory (a robot's bag), each bounds-checked:
// a read past the end throws fleetmerge::Error naming the file, the offset and what was read.
#pragma once

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

namespace fleetmerge {

class BinaryFile {
 public:
  explicit BinaryFile(const std::filesystem::path& path);
  const std::filesystem::path& path() const { return path_; }
  std::uint64_t size() const { return size_; }
  // n bytes at `offset`; `what` names them in the error of a short file.
  std::string Read(std::uint64_t offset, std::uint64_t n, const char* what);

 private:
  std::filesystem::path path_;
  std::ifstream in_;
  std::uint64_t size_ = 0;
};

}  // namespace fleetmerge
