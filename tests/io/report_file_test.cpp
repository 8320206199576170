// report.json as `fleetmerge merge` writes it (pipeline/report_json.hpp) read back: maps,
// components and poses, extra fields ignored; every malformed report fails naming the file and
// the field.
#include "io/report_file.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "core/error.hpp"
#include "tests/io/io_test_util.hpp"
#include "tests/support/shared_data.hpp"

namespace fleetmerge {
namespace {

namespace fs = std::filesystem;
namespace ft = fleetmerge::testing;
using nlohmann::json;

// Two maps merged into component 0, a third alone in component 1, with the fields merge writes.
json ValidReport() {
  return json::parse(R"({
    "job": "merge", "resolution": 0.05,
    "maps": [
      {"name": "a", "source": "a.yaml", "component": 0, "pose": {"x": 0, "y": 0, "yaw": 0}},
      {"name": "b", "source": "b.yaml", "component": 0, "pose": {"x": 1.5, "y": -2, "yaw": 0.25}},
      {"name": "c", "source": "c.yaml", "component": 1, "pose": {"x": 0, "y": 0, "yaw": 0}}],
    "components": [
      {"id": 0, "maps": ["a", "b"], "reference": "a", "merged_map": "merged_0.yaml"},
      {"id": 1, "maps": ["c"], "reference": "c"}],
    "pairs": [], "timing_ms": {"total": 1}})");
}

class ReportFileTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = ft::MakeTempDir("report_file"); }
  fs::path Write(const std::string& text) const {
    ft::WriteFile(dir_ / "report.json", text);
    return dir_ / "report.json";
  }
  std::string ErrorOf(const std::string& text) const {
    try {
      LoadMergeReport(Write(text));
    } catch (const Error& e) {
      return e.what();
    }
    ADD_FAILURE() << "accepted:\n" << text;
    return "";
  }
  fs::path dir_;
};

TEST_F(ReportFileTest, ReadsMapsComponentsAndPoses) {
  const MergeReport report = LoadMergeReport(Write(ValidReport().dump()));
  ASSERT_EQ(report.maps.size(), 3u);
  EXPECT_EQ(report.maps[1].name, "b");
  EXPECT_EQ(report.maps[1].component, 0);
  EXPECT_EQ(report.maps[1].T_component_map.x_m(), 1.5);
  EXPECT_EQ(report.maps[1].T_component_map.y_m(), -2.0);
  EXPECT_EQ(report.maps[1].T_component_map.yaw_rad(), 0.25);
  EXPECT_EQ(report.maps[2].component, 1);
  ASSERT_EQ(report.components.size(), 2u);
  EXPECT_EQ(report.components[0].maps, (std::vector<std::string>{"a", "b"}));
  EXPECT_EQ(report.components[1].maps, (std::vector<std::string>{"c"}));
}

TEST_F(ReportFileTest, MalformedReportsNameFileAndField) {
  struct Case {
    std::function<void(json&)> mutate;
    std::string expected;
  };
  const std::vector<Case> cases = {
      {[](json& r) { r.erase("maps"); }, "field 'maps': missing: expected a list"},
      {[](json& r) { r["components"] = 3; }, "field 'components': expected a list, got 3"},
      {[](json& r) { r["maps"][1].erase("pose"); }, "field 'maps[1].pose': missing"},
      {[](json& r) { r["maps"][1]["pose"]["yaw"] = "abc"; },
       "field 'maps[1].pose.yaw': expected a finite number, got \"abc\""},
      {[](json& r) { r["maps"][0]["name"] = ""; },
       "field 'maps[0].name': expected a non-empty string"},
      {[](json& r) { r["maps"][2]["name"] = "a"; },
       "field 'maps[2].name': map name 'a' appears twice"},
      {[](json& r) { r["maps"][0]["component"] = -1; },
       "field 'maps[0].component': expected an integer >= 0, got -1"},
      {[](json& r) { r["maps"][0]["component"] = 1; },
       "field 'components[0].maps[0]': 'a' has component 1 in 'maps'"},
      {[](json& r) { r["components"][1]["maps"][0] = "z"; },
       "field 'components[1].maps[0]': 'z' is not one of the report's maps"},
      {[](json& r) { r["components"][1]["id"] = 5; },
       "field 'components[1].id': expected 1 (its index), got 5"},
      {[](json& r) { r["components"].erase(1); },
       "field 'maps[2].component': map 'c' is not listed (once) in components[1]"},
      {[](json& r) {
         r["maps"][1]["pose"] = {1, 2, 3};
       },
       "field 'maps[1].pose': expected an object {x, y, yaw}"},
  };
  for (const Case& c : cases) {
    json report = ValidReport();
    c.mutate(report);
    const std::string message = ErrorOf(report.dump());
    EXPECT_TRUE(ft::StartsWith(message, (dir_ / "report.json").string() + ": ")) << report;
    EXPECT_TRUE(ft::Contains(message, c.expected)) << report;
  }
  EXPECT_TRUE(ft::Contains(ErrorOf("{\"maps\": ["), "malformed JSON"));
  EXPECT_TRUE(ft::Contains(ErrorOf("[1, 2]"), "expected a report object"));
  try {
    LoadMergeReport(dir_ / "absent.json");
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_TRUE(ft::Contains(e.what(), "absent.json: cannot open report"));
  }
}

}  // namespace
}  // namespace fleetmerge
