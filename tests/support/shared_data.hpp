// Access to ../shared/data/maps for tests. Tests that need the real maps call
// FLEETMERGE_REQUIRE_SHARED_MAPS() first: without the folder they are skipped with a visible
// message naming the folder, never silently passed.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <optional>
#include <string>

namespace fleetmerge::testing {

// The shared maps folder, or nullopt when absent. FLEETMERGE_SHARED_MAPS overrides the default
// (the folder beside the source tree, fixed at configure time).
std::optional<std::filesystem::path> SharedMapsDir();
std::string SharedMapsDirDescription();

// `full` scaled by FLEETMERGE_TEST_SCALE (a number in (0, 1], default 1), at least `minimum`:
// the sanitizer build runs the heavy accuracy tests with fewer trials (every test still runs).
int ScaledCount(int full, int minimum);

// A fresh, empty folder for one test's files.
std::filesystem::path MakeTempDir(const std::string& name);

}  // namespace fleetmerge::testing

#define FLEETMERGE_REQUIRE_SHARED_MAPS()                                                \
  do {                                                                                  \
    if (!::fleetmerge::testing::SharedMapsDir()) {                                      \
      GTEST_SKIP() << "SKIPPED: shared maps not found at "                              \
                   << ::fleetmerge::testing::SharedMapsDirDescription()                 \
                   << " (set FLEETMERGE_SHARED_MAPS or put ../shared beside the repo)"; \
    }                                                                                   \
  } while (0)
