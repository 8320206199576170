// Shared by the libFuzzer targets: one scratch folder per process, files rewritten per input.
// Every target is an LLVMFuzzerTestOneInput in its own file; built with clang's -fsanitize=fuzzer
// it is a fuzzer (scripts/fuzz.sh), built with replay_main.cpp it replays the seed corpus and the
// kept crashing inputs as a ctest test in every build.
#pragma once

#include <stdlib.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

namespace fleetmerge::fuzz {

inline const std::filesystem::path& ScratchDir() {
  static const std::filesystem::path dir = [] {
    std::string pattern =
        (std::filesystem::temp_directory_path() / "fleetmerge_fuzz_XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) abort();
    return std::filesystem::path(pattern);
  }();
  return dir;
}

inline void WriteBytes(const std::filesystem::path& path, const char* data, std::size_t size) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(data, static_cast<std::streamsize>(size));
}

// Splits a fuzzer input at the first `separator`: (before, after); no separator: (all, "").
inline std::pair<std::string, std::string> Split(const std::uint8_t* data, std::size_t size,
                                                 const std::string& separator) {
  const std::string all(reinterpret_cast<const char*>(data), size);
  const std::size_t at = all.find(separator);
  if (at == std::string::npos) return {all, ""};
  return {all.substr(0, at), all.substr(at + separator.size())};
}

}  // namespace fleetmerge::fuzz
