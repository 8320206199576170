#include "tests/support/shared_data.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <random>

namespace fleetmerge::testing {
namespace {

std::filesystem::path ConfiguredDir() {
  if (const char* env = std::getenv("FLEETMERGE_SHARED_MAPS"); env != nullptr && *env != '\0') {
    return env;
  }
  return FLEETMERGE_SHARED_MAPS_DIR;
}

}  // namespace

std::optional<std::filesystem::path> SharedMapsDir() {
  const std::filesystem::path dir = ConfiguredDir();
  std::error_code ec;
  if (std::filesystem::is_regular_file(dir / "SOURCES.md", ec)) return dir;
  return std::nullopt;
}

std::string SharedMapsDirDescription() { return ConfiguredDir().string(); }

std::filesystem::path MakeTempDir(const std::string& name) {
  std::filesystem::path base = std::filesystem::temp_directory_path();
  if (const char* env = std::getenv("FLEETMERGE_TEST_TMP"); env != nullptr && *env != '\0') {
    base = env;
  }
  std::random_device rd;
  const std::filesystem::path dir = base / (name + "_" + std::to_string(rd()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

int ScaledCount(int full, int minimum) {
  double scale = 1.0;
  if (const char* env = std::getenv("FLEETMERGE_TEST_SCALE"); env != nullptr && *env != '\0') {
    scale = std::strtod(env, nullptr);
    if (!(scale > 0.0 && scale <= 1.0)) scale = 1.0;
  }
  return std::max(minimum, static_cast<int>(std::lround(full * scale)));
}

}  // namespace fleetmerge::testing
