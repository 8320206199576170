// pipeline/html_report: what report.html's page is given, checked without a browser (the page
// itself is checked in Chromium by tests/browser/report_browser_test.cpp): the map images' pixel
// layout, the pose graph's node positions, the options listed as changed, and names that look
// like markup staying data.
#include "pipeline/html_report.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>

#include "tests/support/files.hpp"
#include "tests/support/shared_data.hpp"

namespace fleetmerge {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

json EmbeddedData(const std::string& html) {
  const std::string open = "<script type=\"application/json\" id=\"fleetmerge-data\">";
  const std::size_t begin = html.find(open);
  const std::size_t end = html.find("</script>", begin);
  if (begin == std::string::npos || end == std::string::npos) return json();
  return json::parse(html.substr(begin + open.size(), end - begin - open.size()));
}

int Count(const std::string& text, const std::string& what) {
  int n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// A one-map page around `grid` (a minimal report.json).
HtmlReport OneMapPage(const OccupancyGrid& grid, const std::string& name) {
  HtmlReport page;
  page.title = name;
  page.report = {
      {"job", name},
      {"maps", {{{"name", name}, {"component", 0}, {"pose", {{"x", 0}, {"y", 0}, {"yaw", 0}}}}}},
      {"components", {{{"id", 0}, {"maps", {name}}}}},
      {"pairs", json::array()}};
  page.maps.push_back({&grid, Pose2(), "in.yaml", grid.width(), grid.height(), 0.05});
  page.components.push_back({{0}, nullptr, ""});
  return page;
}

TEST(HtmlReport, MapImageHasOnePixelPerCellWithTheTopRowFirst) {
  // 3 x 4 cells; grid row 0 is the bottom: occupied at (1, 0), free at (0, 3), rest unknown.
  OccupancyGrid grid(GridGeometry(0.05, {3, 4}, Pose2(1.0, 2.0, 0.3)));
  grid.set({1, 0}, CellState::kOccupied);
  grid.set({0, 3}, CellState::kFree);
  const fs::path dir = testing::MakeTempDir("html_report_image");
  const std::vector<std::string> written = WriteHtmlReport(OneMapPage(grid, "m"), dir, {});
  EXPECT_EQ(written, (std::vector<std::string>{"report_map_0.png", "report.html"}));
  const cv::Mat image = cv::imread((dir / "report_map_0.png").string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(image.type(), CV_8UC4);
  ASSERT_EQ(image.cols, 3);
  ASSERT_EQ(image.rows, 4);
  const auto at = [&](int row, int col) { return image.at<cv::Vec4b>(row, col); };
  EXPECT_EQ(at(3, 1), cv::Vec4b(0, 0, 0, 255)) << "occupied: opaque black, bottom row last";
  EXPECT_EQ(at(0, 0)[3], 255) << "free: opaque";
  EXPECT_GT(at(0, 0)[0], 200) << "free: near-white";
  for (const auto& [row, col] : {std::pair{0, 1}, {1, 1}, {2, 2}, {3, 0}}) {
    EXPECT_EQ(at(row, col)[3], 0) << "unknown: transparent at " << row << ", " << col;
  }
  // The page places the image by the grid's geometry, given beside it.
  const json map = EmbeddedData(HtmlReportText(OneMapPage(grid, "m"))).at("page").at("maps")[0];
  EXPECT_EQ(map.at("width"), 3);
  EXPECT_EQ(map.at("height"), 4);
  EXPECT_DOUBLE_EQ(map.at("T_map_grid").at("yaw").get<double>(), 0.3);
  // Known cells: columns 0-1 of rows 0-3, i.e. image box [u0, v0, u1, v1] = [0, 0, 2, 4].
  EXPECT_EQ(map.at("known_box"), json({0, 0, 2, 4}));
  EXPECT_EQ(map.at("known_cells"), 2);
}

TEST(HtmlReport, MapWithoutCellsGetsNoImageAndDoesNotFailThePage) {
  const OccupancyGrid empty(GridGeometry(0.05, {0, 0}));
  const fs::path dir = testing::MakeTempDir("html_report_empty");
  std::vector<std::string> written;
  ASSERT_NO_THROW(written = WriteHtmlReport(OneMapPage(empty, "m"), dir, {}));
  EXPECT_EQ(written, (std::vector<std::string>{"report.html"}));
  EXPECT_FALSE(fs::exists(dir / "report_map_0.png"));
  EXPECT_TRUE(EmbeddedData(HtmlReportText(OneMapPage(empty, "m")))
                  .at("page")
                  .at("maps")[0]
                  .at("image")
                  .is_null());
}

TEST(HtmlReport, MapImagesThenPageWriteWhatTheWholeReportWrites) {
  // The job writes the images while its merged maps are written and the page after the report
  // (pipeline/job_run.cpp); `pair --out` writes both at once. The same files either way.
  OccupancyGrid a(GridGeometry(0.05, {7, 5}, Pose2(0.5, -1.0, 0.2)));
  a.set({2, 1}, CellState::kOccupied);
  a.set({4, 3}, CellState::kFree);
  const OccupancyGrid empty(GridGeometry(0.05, {0, 0}));
  OccupancyGrid b(GridGeometry(0.05, {3, 9}), CellState::kFree);
  b.set({1, 8}, CellState::kOccupied);
  HtmlReport page = OneMapPage(a, "a");
  page.maps.push_back({&empty, Pose2(), "empty.yaml", 0, 0, 0.05});
  page.maps.push_back({&b, Pose2(1.0, 0.0, 0.0), "b.yaml", 3, 9, 0.05});
  const fs::path whole = testing::MakeTempDir("html_report_whole");
  const fs::path parts = testing::MakeTempDir("html_report_parts");
  const std::vector<std::string> written_whole = WriteHtmlReport(page, whole, {}, 2);
  std::vector<std::string> written_parts = WriteHtmlMapImages({&a, &empty, &b}, parts, {}, 2);
  for (const std::string& name : WriteHtmlPage(page, parts, {})) written_parts.push_back(name);
  EXPECT_EQ(written_whole,
            (std::vector<std::string>{"report_map_0.png", "report_map_2.png", "report.html"}));
  EXPECT_EQ(written_parts, written_whole);
  for (const std::string& name : written_whole) {
    EXPECT_EQ(testing::ReadFile(parts / name), testing::ReadFile(whole / name)) << name;
  }
  EXPECT_FALSE(fs::exists(parts / "report_map_1.png"));
  // Each image is its own map's (by index, whichever thread wrote it): b's 3 x 9 cells with its
  // wall at the top row (grid row 8).
  const cv::Mat image = cv::imread((parts / "report_map_2.png").string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(image.type(), CV_8UC4);
  EXPECT_EQ(image.cols, 3);
  EXPECT_EQ(image.rows, 9);
  EXPECT_EQ(image.at<cv::Vec4b>(0, 1), cv::Vec4b(0, 0, 0, 255));
}

TEST(HtmlReport, GraphNodeSitsAtTheMapsKnownCentreInPreviewPixels) {
  // A 10 x 10 map at 0.1 m, every cell known: its centre is (0.5, 0.5) in its map frame, and
  // (1.5, 2.5) in the merged frame under T = (1, 2, 0). The merged grid's origin is (1, 2), 0.1 m
  // cells, 20 x 20: column 5, and row 20 - 5 = 15 counted from the top.
  OccupancyGrid map(GridGeometry(0.1, {10, 10}), CellState::kFree);
  OccupancyGrid merged(GridGeometry(0.1, {20, 20}, Pose2(1.0, 2.0, 0.0)), CellState::kFree);
  HtmlReport page = OneMapPage(map, "m");
  page.maps[0].T_component_map = Pose2(1.0, 2.0, 0.0);
  page.components[0] = {{0}, &merged, "merged_0_preview.png"};
  const json component = EmbeddedData(HtmlReportText(page)).at("page").at("components")[0];
  ASSERT_EQ(component.at("nodes").size(), 1u);
  EXPECT_NEAR(component.at("nodes")[0].at("u").get<double>(), 5.0, 1e-9);
  EXPECT_NEAR(component.at("nodes")[0].at("v").get<double>(), 15.0, 1e-9);
  EXPECT_EQ(component.at("merged").at("image"), "merged_0_preview.png");
  // The legend's colour is the preview's first colour (Tableau blue, pipeline/preview.hpp).
  EXPECT_EQ(component.at("colours")[0], "#1f77b4");
}

TEST(HtmlReport, ChangedOptionsListsOnlyWhatDiffersFromTheDefaults) {
  EXPECT_EQ(ChangedOptions(FleetOptions()), json::object());
  FleetOptions options;
  options.omega_threshold = 0.95;
  options.fusion = FusionMode::kMax;
  options.pair.hypotheses.hough.n_theta = 360;
  const json changed = ChangedOptions(options);
  EXPECT_EQ(changed.size(), 3u) << changed.dump();
  EXPECT_EQ(changed.at("omega_threshold"), json({{"value", 0.95}, {"default", 0.9}}));
  EXPECT_EQ(changed.at("fusion"), json({{"value", "max"}, {"default", "log_odds"}}));
  EXPECT_EQ(changed.at("hough.n_theta"), json({{"value", 360}, {"default", 180}}));
}

TEST(HtmlReport, NamesThatLookLikeMarkupStayData) {
  OccupancyGrid grid(GridGeometry(0.05, {2, 2}), CellState::kFree);
  const std::string name = "</script><script>alert(1)</script>";
  const std::string html = HtmlReportText(OneMapPage(grid, name));
  // The template's two </script> and no more: the name cannot end the data element.
  EXPECT_EQ(Count(html, "</script>"), 2);
  EXPECT_EQ(EmbeddedData(html).at("report").at("maps")[0].at("name"), name);
  // A name that is not UTF-8 is written with U+FFFD instead of failing the job.
  const json data = EmbeddedData(HtmlReportText(OneMapPage(grid, "run\xff")));
  EXPECT_EQ(data.at("report").at("maps")[0].at("name"), "run\xef\xbf\xbd");
}

}  // namespace
}  // namespace fleetmerge
