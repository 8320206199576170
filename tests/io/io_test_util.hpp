// Helpers shared by the io/ tests: fixtures, rendering grids as text (file reads and writes:
// tests/support/files.hpp).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "core/occupancy_grid.hpp"
#include "tests/support/files.hpp"

namespace fleetmerge::testing {

// The checked-in fixtures (tests/data/maps), fixed at configure time.
inline std::filesystem::path FixtureDir() {
  return std::filesystem::path(FLEETMERGE_TEST_DATA_DIR) / "maps";
}

// A map YAML naming `image` with the given extra lines (e.g. "negate: 1\n").
inline std::string MapYaml(const std::string& image, const std::string& extra = "") {
  return "image: " + image + "\nresolution: 0.05\norigin: [0.0, 0.0, 0.0]\n" + extra;
}

// The grid as text in image order (top row first): '#' occupied, '.' free, '?' unknown.
inline std::vector<std::string> RenderTopFirst(const OccupancyGrid& grid) {
  std::vector<std::string> rows;
  for (int j = grid.height() - 1; j >= 0; --j) {
    std::string row;
    for (int i = 0; i < grid.width(); ++i) {
      switch (grid.at({i, j})) {
        case CellState::kOccupied:
          row += '#';
          break;
        case CellState::kFree:
          row += '.';
          break;
        case CellState::kUnknown:
          row += '?';
          break;
        default:
          row += 'X';
      }
    }
    rows.push_back(row);
  }
  return rows;
}

// Names of the files in a folder (to check that no temporary file is left behind).
inline std::vector<std::string> FileNames(const std::filesystem::path& folder) {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    names.push_back(entry.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

// Assertions on error messages, with the whole message in the failure output.
inline ::testing::AssertionResult Contains(const std::string& text, const std::string& part) {
  if (text.find(part) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "'" << text << "' does not contain '" << part << "'";
}

inline ::testing::AssertionResult StartsWith(const std::string& text, const std::string& prefix) {
  if (text.rfind(prefix, 0) == 0) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "'" << text << "' does not start with '" << prefix << "'";
}

}  // namespace fleetmerge::testing
