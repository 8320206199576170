// Whole-file reads and writes for tests (binary, no checks: a test asserts on what it reads).
#pragma once

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace fleetmerge::testing {

inline void WriteFile(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out << bytes;
}

inline std::string ReadFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

}  // namespace fleetmerge::testing
