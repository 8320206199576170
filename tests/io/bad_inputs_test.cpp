// The catalogue of malformed inputs (tests/data/bad, made by its generate.py): every case must
// fail with fleetmerge::Error naming the file and carrying its expected text, print nothing else
// (OpenCV and yaml-cpp must not write their own messages to stderr), and never crash. A case
// whose case.txt says `loads` must load.
//
// Each case names its reader (map, job, octree); a new input format is one more entry in
// Readers() and more folders made by generate.py.
#include <gtest/gtest.h>
#include <octomap/OcTree.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "io/job_file.hpp"
#include "io/map_inputs.hpp"
#include "io/map_io.hpp"
#include "io/octree_io.hpp"

namespace fleetmerge {
namespace {
namespace fs = std::filesystem;

const std::map<std::string, std::function<void(const fs::path&)>>& Readers() {
  static const std::map<std::string, std::function<void(const fs::path&)>> readers = {
      {"map", [](const fs::path& path) { LoadMap(path); }},
      {"job", [](const fs::path& path) { LoadJobFile(path); }},
      {"octree", [](const fs::path& path) { LoadOctree(path); }},
      // Every map topic of the bag, as `merge --out BAG` loads them (io/map_inputs.hpp).
      {"bag",
       [](const fs::path& path) {
         for (const JobMap& map : ExpandMapInputs({{path, path, "", {}}})) LoadJobMap(map);
       }},
  };
  return readers;
}

struct BadCase {
  std::string name;
  fs::path folder;
  std::string reader;
  std::string input;
  std::string error;  // empty: the input must load
};

std::vector<BadCase> Catalogue() {
  std::vector<BadCase> cases;
  const fs::path root = fs::path(FLEETMERGE_TEST_DATA_DIR) / "bad";
  for (const auto& entry : fs::directory_iterator(root)) {
    if (!fs::exists(entry.path() / "case.txt")) continue;
    BadCase c{entry.path().filename().string(), entry.path(), "", "", ""};
    std::ifstream in(entry.path() / "case.txt");
    for (std::string line; std::getline(in, line);) {
      if (line.rfind("reader: ", 0) == 0) c.reader = line.substr(8);
      if (line.rfind("input: ", 0) == 0) c.input = line.substr(7);
      if (line.rfind("error: ", 0) == 0) c.error = line.substr(7);
    }
    cases.push_back(c);
  }
  std::sort(cases.begin(), cases.end(),
            [](const BadCase& a, const BadCase& b) { return a.name < b.name; });
  return cases;
}

class BadInputTest : public ::testing::TestWithParam<BadCase> {};

TEST_P(BadInputTest, FailsWithItsMessageAndNothingElse) {
  const BadCase& c = GetParam();
  ASSERT_EQ(Readers().count(c.reader), 1u) << c.name << ": unknown reader '" << c.reader << "'";
  const fs::path input = c.folder / c.input;
  std::string message;
  ::testing::internal::CaptureStderr();
  try {
    Readers().at(c.reader)(input);
  } catch (const Error& e) {
    message = e.what();
  }
  const std::string stderr_text = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(stderr_text, "") << "a reader printed on its own";
  if (c.error.empty()) {
    EXPECT_EQ(message, "") << c.name << " should load";
    return;
  }
  ASSERT_NE(message, "") << c.name << ": no error";
  EXPECT_NE(message.find(c.error), std::string::npos) << c.name << ": " << message;
  EXPECT_NE(message.find(c.folder.filename().string()), std::string::npos)
      << "the message names the file: " << message;
}

INSTANTIATE_TEST_SUITE_P(Catalogue, BadInputTest, ::testing::ValuesIn(Catalogue()),
                         [](const ::testing::TestParamInfo<BadCase>& info) {
                           return info.param.name;
                         });

TEST(BadInputCatalogue, CoversEveryReader) {
  std::map<std::string, int> per_reader;
  for (const BadCase& c : Catalogue()) ++per_reader[c.reader];
  for (const auto& [reader, unused] : Readers()) {
    EXPECT_GE(per_reader[reader], 10) << "reader '" << reader << "' has few malformed cases";
  }
}

}  // namespace
}  // namespace fleetmerge
