// report.html (issue 12) checked in a real browser: the four TurtleBot3 corridor runs of
// configs/four_robots.yaml are merged (run4 stays unmerged), and headless Chromium opens the
// result folder's report.html from disk (tests/browser/report_page_driver.js drives it over the
// DevTools pipe). The page must load with no console error and no request outside the folder,
// look like something (the screenshot is not blank and shows the merged map's colours), list
// every map and every pair with report.json's decision, show the unmerged map with its best
// candidate, and, when a pair is clicked, draw its overlay where the hypothesis puts the maps:
// every occupied cell of both input maps, carried through the pose in report.json and the
// page's own view matrix, must land on a pixel of its map's wall colour in the screenshot (and
// under a wrong pose most must not: the check can fail). The same for a `pair --out` page.
//
// The example job configs/site_with_priors.yaml is merged and opened too: its run4 is placed by
// its known start pose alone, and the merged map's viewer must draw its node with the dashed
// ring (and only its node), where report.json's pose puts run4's known cells.
//
// Skips with a message when Chromium or Node is not installed (scripts/install_deps.sh
// installs both) or the shared maps are absent. With FLEETMERGE_UPDATE_DOCS_SCREENSHOT=1 it
// also writes the README's screenshot, docs/images/report.png.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "io/map_io.hpp"
#include "io/result_folder.hpp"
#include "pipeline/preview.hpp"
#include "tests/support/files.hpp"
#include "tests/support/fleetmerge_cli.hpp"
#include "tests/support/shared_data.hpp"

namespace fleetmerge {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using testing::ShellQuote;

// The first of `names` found as an executable file on PATH (or the absolute path given).
std::optional<fs::path> FindProgram(const std::vector<std::string>& names) {
  const char* path_env = std::getenv("PATH");
  for (const std::string& name : names) {
    if (name.empty()) continue;
    if (name.front() == '/') {
      if (fs::is_regular_file(name)) return fs::path(name);
      continue;
    }
    std::string dirs = path_env ? path_env : "/usr/bin:/bin";
    std::size_t start = 0;
    while (start <= dirs.size()) {
      const std::size_t end = std::min(dirs.find(':', start), dirs.size());
      const fs::path candidate = fs::path(dirs.substr(start, end - start)) / name;
      if (fs::is_regular_file(candidate)) return candidate;
      start = end + 1;
    }
  }
  return std::nullopt;
}

std::optional<fs::path> Chromium() {
  const char* chosen = std::getenv("FLEETMERGE_CHROMIUM");
  if (chosen && *chosen) return FindProgram({chosen});
  return FindProgram({"chromium", "chromium-browser", "google-chrome"});
}

fs::path SharedMap(const std::string& stem) { return *testing::SharedMapsDir() / (stem + ".yaml"); }

// The page's inline data: the JSON in <script id="fleetmerge-data">.
json EmbeddedData(const std::string& html) {
  const std::string open = "<script type=\"application/json\" id=\"fleetmerge-data\">";
  const std::size_t begin = html.find(open);
  if (begin == std::string::npos) return json();
  const std::size_t end = html.find("</script>", begin);
  if (end == std::string::npos) return json();
  return json::parse(html.substr(begin + open.size(), end - begin - open.size()));
}

struct DriverRun {
  json result;  // the driver's JSON (empty on failure)
  std::string error;
  double wall_s = 0.0;
};

// Opens `folder`/report.html in Chromium, clicks the table rows of `clicks` (a, b), and leaves
// the screenshots in `shots`.
DriverRun Drive(const fs::path& chromium, const fs::path& folder, const fs::path& shots,
                const std::vector<std::pair<std::string, std::string>>& clicks) {
  fs::create_directories(shots);
  std::string command = "node " + ShellQuote(std::string(FLEETMERGE_REPORT_DRIVER)) + " " +
                        ShellQuote(chromium) + " " + ShellQuote(folder) + " " + ShellQuote(shots);
  for (const auto& [a, b] : clicks) command += " " + ShellQuote(a) + " " + ShellQuote(b);
  const auto start = std::chrono::steady_clock::now();
  const testing::CommandResult run = testing::RunCommand(command);
  DriverRun out;
  out.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (run.exit_code != 0) {
    out.error = "driver failed (" + std::to_string(run.exit_code) + "): " + run.err;
    return out;
  }
  try {
    out.result = json::parse(run.out);
  } catch (const std::exception& e) {
    out.error = std::string("driver output is not JSON: ") + e.what() + "\n" + run.out;
  }
  return out;
}

// ---- Where the overlay's pixels must be. The page tints map a blue and map b orange (walls in
// the colour, free cells screened to near-white, 235 grey), draws a, multiplies b onto it, and
// puts grey behind both: a's walls show as A, A x paleB or A x B; b's as B, B x paleA or A x B.
using Rgb = cv::Vec3i;
const Rgb kA(31, 119, 180), kB(255, 127, 14);
Rgb Pale(const Rgb& c) {
  Rgb out;
  for (int k = 0; k < 3; ++k) out[k] = 255 - (255 - 235) * (255 - c[k]) / 255;
  return out;
}
Rgb Multiply(const Rgb& x, const Rgb& y) {
  Rgb out;
  for (int k = 0; k < 3; ++k) out[k] = x[k] * y[k] / 255;
  return out;
}
const std::vector<Rgb> kWallOfA = {kA, Multiply(kA, Pale(kB)), Multiply(kA, kB)};
const std::vector<Rgb> kWallOfB = {kB, Multiply(kB, Pale(kA)), Multiply(kA, kB)};

bool Near(const cv::Vec3b& bgr, const Rgb& rgb, int tolerance) {
  return std::abs(bgr[2] - rgb[0]) <= tolerance && std::abs(bgr[1] - rgb[1]) <= tolerance &&
         std::abs(bgr[0] - rgb[2]) <= tolerance;
}

struct Hits {
  int considered = 0, hits = 0;
  double fraction() const { return considered ? static_cast<double>(hits) / considered : 0.0; }
};

// Carries every occupied cell centre of `grid` by T_a_m into a's map frame, then by the page's
// view matrix [a, b, c, d, e, f] (world = (x, -y) in metres -> device pixels of the canvas) into
// the screenshot, and counts the cells whose pixel has one of `colours`. Cells landing outside
// the screenshot or under the viewer's buttons (top-left corner) are not counted.
Hits WallHits(const cv::Mat3b& shot, const json& view, const OccupancyGrid& grid,
              const Pose2& T_a_m, const std::vector<Rgb>& colours) {
  const double m[6] = {view[0], view[1], view[2], view[3], view[4], view[5]};
  Hits hits;
  for (const Eigen::Array2i& cell : grid.CellsIn(CellState::kOccupied)) {
    const Eigen::Vector2d p = T_a_m * grid.geometry().CellCenter(cell);
    const double wx = p.x(), wy = -p.y();
    const int x = static_cast<int>(std::floor(m[0] * wx + m[2] * wy + m[4]));
    const int y = static_cast<int>(std::floor(m[1] * wx + m[3] * wy + m[5]));
    if (x < 0 || y < 0 || x >= shot.cols || y >= shot.rows) continue;
    if (x < 100 && y < 70) continue;  // the "fit" button
    ++hits.considered;
    for (const Rgb& colour : colours) {
      if (Near(shot(y, x), colour, 40)) {
        ++hits.hits;
        break;
      }
    }
  }
  return hits;
}

Pose2 PoseOf(const json& j) { return Pose2(j.at("x"), j.at("y"), j.at("yaw")); }

// The hypothesis a click on a pair's row shows first: the edge's when accepted, else the best.
int FirstShown(const json& pair) {
  return pair.value("accepted", false) ? pair.value("edge_hypothesis", 0) : 0;
}

// The overlay of a clicked pair at hypothesis h: both maps' walls where report.json's
// hypothesis puts them.
void ExpectOverlayWhereTheHypothesisPutsIt(const json& click, const json& pair, int h,
                                           const fs::path& shots, const LoadedMap& a,
                                           const LoadedMap& b) {
  SCOPED_TRACE(pair.at("a").get<std::string>() + " / " + pair.at("b").get<std::string>() +
               " hypothesis " + std::to_string(h + 1));
  EXPECT_EQ(click.at("state"), "drawn");
  ASSERT_EQ(click.at("hypothesis").get<int>(), h);
  EXPECT_EQ(click.at("hypotheses").size(), pair.at("hypotheses").size()) << click.dump();
  const cv::Mat3b shot = cv::imread((shots / click.at("screenshot").get<std::string>()).string());
  ASSERT_FALSE(shot.empty());
  const Pose2 T_a_b = PoseOf(pair.at("hypotheses").at(h));
  const Hits on_a = WallHits(shot, click.at("view"), a.grid, Pose2(), kWallOfA);
  const Hits on_b = WallHits(shot, click.at("view"), b.grid, T_a_b, kWallOfB);
  std::cout << "[ overlay  ] walls on their pixels: a " << on_a.hits << "/" << on_a.considered
            << ", b " << on_b.hits << "/" << on_b.considered << "\n";
  ASSERT_GT(on_a.considered, 500);
  ASSERT_GT(on_b.considered, 500);
  EXPECT_GE(on_a.fraction(), 0.9) << on_a.hits << " of " << on_a.considered;
  EXPECT_GE(on_b.fraction(), 0.9) << on_b.hits << " of " << on_b.considered;
  // The same check under a pose off by 90 degrees: b's walls are mostly not there.
  const Hits wrong =
      WallHits(shot, click.at("view"), b.grid, T_a_b * Pose2(0, 0, M_PI / 2), kWallOfB);
  EXPECT_LT(wrong.fraction(), 0.5) << wrong.hits << " of " << wrong.considered;
}

void ExpectNoConsoleErrorAndNothingFetchedOutside(const json& result, const fs::path& folder) {
  for (const json& message : result.at("console")) {
    const std::string level = message.at("level");
    EXPECT_TRUE(level != "error" && level != "assert" && level != "warning") << message.dump();
  }
  // The folder as the driver names it (absolute) or resolved (symbolic links followed).
  const std::string inside = "file://" + fs::absolute(folder).lexically_normal().string() + "/";
  const std::string resolved = "file://" + fs::weakly_canonical(folder).string() + "/";
  ASSERT_FALSE(result.at("requests").empty());
  for (const json& url : result.at("requests")) {
    const std::string u = url;
    EXPECT_TRUE(u.rfind(inside, 0) == 0 || u.rfind(resolved, 0) == 0 || u.rfind("data:", 0) == 0)
        << u << " is outside " << inside;
  }
}

// One merge of the four corridor runs and one browser session over its page, shared by the
// tests below (each asserts one part of what the session saw).
struct Session {
  fs::path dir, out, shots;
  json report;
  std::string html;
  DriverRun browser;
  bool browser_ran = false;
  std::optional<fs::path> chromium;
};

Session& Shared() {
  static Session* session = [] {
    auto* s = new Session;
    s->dir = testing::MakeTempDir("report_browser");
    s->out = s->dir / "out";
    s->shots = s->dir / "shots";
    const fs::path job = s->dir / "four_robots.yaml";
    std::string yaml = "name: four_robots\nmaps:\n";
    for (int k = 1; k <= 4; ++k) {
      yaml += "  - {path: " + SharedMap("robotis_corridor_run" + std::to_string(k)).string() +
              ", name: run" + std::to_string(k) + "}\n";
    }
    yaml += "output: " + s->out.string() + "\n";
    testing::WriteFile(job, yaml);
    const testing::CommandResult merge = testing::Fleetmerge("merge --quiet " + ShellQuote(job));
    if (merge.exit_code != 0) {
      ADD_FAILURE() << merge.both();
      return s;
    }
    s->report = json::parse(testing::ReadFile(s->out / "report.json"));
    s->html = testing::ReadFile(s->out / "report.html");
    s->chromium = Chromium();
    return s;
  }();
  return *session;
}

const json& PairOf(const json& report, const std::string& a, const std::string& b) {
  for (const json& p : report.at("pairs")) {
    if (p.at("a") == a && p.at("b") == b) return p;
  }
  throw std::runtime_error("no pair " + a + " " + b);
}

// The pairs clicked: the first accepted one, then run1 / run4 (the refused case), so
// the page is left showing the refused overlay (the README's screenshot).
std::vector<std::pair<std::string, std::string>> Clicks(const json& report) {
  std::vector<std::pair<std::string, std::string>> clicks;
  for (const json& p : report.at("pairs")) {
    if (p.at("accepted").get<bool>()) {
      clicks.emplace_back(p.at("a"), p.at("b"));
      break;
    }
  }
  clicks.emplace_back("run1", "run4");
  return clicks;
}

class ReportPage : public ::testing::Test {
 protected:
  void SetUp() override {
    FLEETMERGE_REQUIRE_SHARED_MAPS();
    ASSERT_FALSE(Shared().report.is_null()) << "the merge failed";
  }
};

class ReportInBrowser : public ReportPage {
 protected:
  void SetUp() override {
    ReportPage::SetUp();
    if (IsSkipped() || HasFatalFailure()) return;
    Session& s = Shared();
    if (!s.chromium || !FindProgram({"node"})) {
      GTEST_SKIP() << "SKIPPED: no browser test: "
                   << (!s.chromium ? "Chromium not found (chromium on PATH or FLEETMERGE_CHROMIUM)"
                                   : "node not found on PATH")
                   << "; scripts/install_deps.sh installs both";
    }
    if (!s.browser_ran) {
      s.browser_ran = true;
      s.browser = Drive(*s.chromium, s.out, s.shots, Clicks(s.report));
      std::cout << "[ browser  ] report.html opened and checked in " << s.browser.wall_s
                << " s (Chromium start to exit)\n";
    }
    ASSERT_TRUE(s.browser.error.empty()) << s.browser.error;
  }
  const json& Result() { return Shared().browser.result; }
};

TEST_F(ReportPage, IsPartOfTheResultSetAndCarriesReportJson) {
  Session& s = Shared();
  const ResultManifest manifest = ReadResultManifest(s.out);
  const std::set<std::string> files(manifest.files.begin(), manifest.files.end());
  EXPECT_EQ(files.count("report.html"), 1u);
  for (std::size_t m = 0; m < s.report.at("maps").size(); ++m) {
    const std::string image = "report_map_" + std::to_string(m) + ".png";
    EXPECT_EQ(files.count(image), 1u) << image;
    // One pixel per cell of the map as compared (the maps' own 5 cm cells here).
    const cv::Mat image_pixels = cv::imread((s.out / image).string(), cv::IMREAD_UNCHANGED);
    const LoadedMap input = LoadMap(SharedMap("robotis_corridor_run" + std::to_string(m + 1)));
    EXPECT_EQ(image_pixels.cols, input.grid.width()) << image;
    EXPECT_EQ(image_pixels.rows, input.grid.height()) << image;
    EXPECT_EQ(image_pixels.channels(), 4) << image;
  }
  // The page's data is report.json (plus the page's own write time, which report.json adds
  // after the page is written).
  const json data = EmbeddedData(s.html);
  ASSERT_TRUE(data.contains("report")) << "no inline data";
  json report = s.report;
  ASSERT_TRUE(report["timing_ms"].contains("report_html"));
  report["timing_ms"].erase("report_html");
  EXPECT_EQ(data.at("report"), report);
  // Offline: no reference to anything outside the folder.
  for (const char* outside : {"http://", "https://", "//cdn", "<link rel=\"stylesheet\""}) {
    EXPECT_EQ(s.html.find(outside), std::string::npos) << outside;
  }
}

TEST_F(ReportInBrowser, OpensWithNoConsoleErrorAndFetchesNothingOutsideTheFolder) {
  ExpectNoConsoleErrorAndNothingFetchedOutside(Result(), Shared().out);
}

TEST_F(ReportInBrowser, ScreenshotShowsTheMergedMap) {
  const Session& s = Shared();
  const cv::Mat3b shot =
      cv::imread((s.shots / Result().at("page_screenshot").get<std::string>()).string());
  ASSERT_FALSE(shot.empty());
  cv::Scalar mean, stddev;
  cv::meanStdDev(shot, mean, stddev);
  EXPECT_GT(stddev[0] + stddev[1] + stddev[2], 60.0) << "a near-uniform screenshot";
  // The merged map's robots' colours (pipeline/preview.hpp) are on screen.
  const int maps_in_component = static_cast<int>(s.report.at("components")[0].at("maps").size());
  for (int k = 0; k < maps_in_component; ++k) {
    const cv::Vec3b bgr = PaletteColour(k);
    int count = 0;
    for (int y = 0; y < shot.rows; ++y) {
      for (int x = 0; x < shot.cols; ++x) {
        count += Near(shot(y, x), Rgb(bgr[2], bgr[1], bgr[0]), 12);
      }
    }
    EXPECT_GT(count, 500) << "robot colour " << k << " hardly on screen";
  }
  if (const char* update = std::getenv("FLEETMERGE_UPDATE_DOCS_SCREENSHOT");
      update && *update == '1') {
    // The README's picture: the pair table with run4's refused overlay on run1, at 1 CSS pixel
    // per pixel.
    const cv::Mat pairs =
        cv::imread((s.shots / Result().at("pairs_screenshot").get<std::string>()).string());
    cv::Mat small;
    cv::resize(pairs, small, cv::Size(), 0.5, 0.5, cv::INTER_AREA);
    const fs::path docs = fs::path(FLEETMERGE_SOURCE_DIR) / "docs" / "images" / "report.png";
    fs::create_directories(docs.parent_path());
    ASSERT_TRUE(cv::imwrite(docs.string(), small, {cv::IMWRITE_PNG_COMPRESSION, 9}));
    std::cout << "[ docs     ] wrote " << docs << " (" << fs::file_size(docs) / 1024 << " KB)\n";
  }
}

TEST_F(ReportInBrowser, ListsEveryMapAndEveryPairWithItsDecision) {
  const Session& s = Shared();
  const json& dom = Result().at("dom");
  std::vector<std::string> names;
  for (const json& m : s.report.at("maps")) names.push_back(m.at("name"));
  EXPECT_EQ(dom.at("input_maps").get<std::vector<std::string>>(), names);
  ASSERT_EQ(dom.at("pairs").size(), s.report.at("pairs").size());
  std::map<std::pair<std::string, std::string>, json> rows;
  for (const json& row : dom.at("pairs")) rows[{row.at("a"), row.at("b")}] = row;
  for (const json& p : s.report.at("pairs")) {
    const auto key = std::make_pair(p.at("a").get<std::string>(), p.at("b").get<std::string>());
    ASSERT_EQ(rows.count(key), 1u) << p.dump();
    const json& row = rows[key];
    EXPECT_EQ(row.at("decision"), p.at("accepted").get<bool>() ? "accepted" : "refused");
    const std::string reason = row.at("cells").back();
    if (p.contains("note")) {
      // The reason as report.json gives it (its "rejected: " prefix reads "refused: ").
      std::string note = p.at("note");
      if (note.rfind("rejected: ", 0) == 0) note = note.substr(10);
      EXPECT_NE(reason.find(note), std::string::npos) << reason << " vs " << p.at("note");
    }
    char omega[16];
    std::snprintf(omega, sizeof omega, "%.3f", p.at("omega").get<double>());
    EXPECT_EQ(row.at("cells")[2], omega);
    EXPECT_EQ(row.at("cells")[3], std::to_string(p.at("overlap_cells").get<long>()));
  }
  // Every merged component with its maps in the legend.
  std::vector<json> merged;
  for (const json& c : s.report.at("components")) {
    if (c.contains("merged_map")) merged.push_back(c.at("maps"));
  }
  ASSERT_EQ(dom.at("components").size(), merged.size());
  for (std::size_t c = 0; c < merged.size(); ++c) {
    EXPECT_EQ(dom.at("components")[c].at("legend"), merged[c]);
  }
}

TEST_F(ReportInBrowser, UnmergedMapIsShownWithItsBestCandidateOverlay) {
  const Session& s = Shared();
  ASSERT_EQ(s.report.at("maps")[3].at("name"), "run4");
  ASSERT_EQ(s.report.at("maps")[3].at("component"), 1) << "run4 stays unmerged in this case";
  const json* best = nullptr;
  for (const json& p : s.report.at("pairs")) {
    if ((p.at("a") == "run4" || p.at("b") == "run4") &&
        (!best || p.at("omega").get<double>() > best->at("omega").get<double>())) {
      best = &p;
    }
  }
  ASSERT_NE(best, nullptr);
  const json& unmerged = Result().at("dom").at("unmerged");
  ASSERT_EQ(unmerged.size(), 1u) << unmerged.dump();
  EXPECT_EQ(unmerged[0].at("map"), "run4");
  EXPECT_EQ(unmerged[0].at("best"),
            best->at("a").get<std::string>() + "|" + best->at("b").get<std::string>());
}

TEST_F(ReportInBrowser, ClickingAPairDrawsItsOverlayWhereItsHypothesisPutsTheMaps) {
  const Session& s = Shared();
  const auto clicks = Clicks(s.report);
  const json& seen = Result().at("clicks");
  ASSERT_EQ(seen.size(), clicks.size());
  for (std::size_t k = 0; k < clicks.size(); ++k) {
    const auto& [a, b] = clicks[k];
    EXPECT_EQ(seen[k].at("pair"), a + "|" + b);
    EXPECT_EQ(seen[k].at("title"), b + " over " + a);
    const auto stem = [](const std::string& name) {
      return "robotis_corridor_run" + name.substr(3);
    };
    const json& pair = PairOf(s.report, a, b);
    ExpectOverlayWhereTheHypothesisPutsIt(seen[k], pair, FirstShown(pair), s.shots,
                                          LoadMap(SharedMap(stem(a))), LoadMap(SharedMap(stem(b))));
  }
}

TEST_F(ReportInBrowser, HypothesisButtonsRedrawTheOverlayAtThatHypothesis) {
  const Session& s = Shared();
  const json& second = Result().at("second");
  ASSERT_TRUE(second.is_object()) << "the second hypothesis was not clicked";
  EXPECT_EQ(second.at("pair"), "run1|run4");
  const json& pair = PairOf(s.report, "run1", "run4");
  ASSERT_GE(pair.at("hypotheses").size(), 2u);
  ExpectOverlayWhereTheHypothesisPutsIt(second, pair, 1, s.shots,
                                        LoadMap(SharedMap("robotis_corridor_run1")),
                                        LoadMap(SharedMap("robotis_corridor_run4")));
}

TEST_F(ReportInBrowser, PairTableSortsByOmega) {
  const Session& s = Shared();
  std::vector<std::pair<double, std::string>> by_omega;
  std::vector<std::string> job_order;
  for (const json& p : s.report.at("pairs")) {
    const std::string key = p.at("a").get<std::string>() + "|" + p.at("b").get<std::string>();
    by_omega.emplace_back(p.at("omega").get<double>(), key);
    job_order.push_back(key);
  }
  std::stable_sort(by_omega.begin(), by_omega.end(),
                   [](const auto& x, const auto& y) { return x.first > y.first; });
  std::vector<std::string> descending;
  for (const auto& [omega, key] : by_omega) descending.push_back(key);
  const std::vector<std::string> ascending(descending.rbegin(), descending.rend());
  const json& sorted = Result().at("sorted");
  EXPECT_EQ(sorted.at("initial").get<std::vector<std::string>>(), job_order);
  EXPECT_EQ(sorted.at("omega_first_click").get<std::vector<std::string>>(), descending);
  EXPECT_EQ(sorted.at("omega_second_click").get<std::vector<std::string>>(), ascending);
}

// `pair --out` writes its own report.html; it opens and draws the best hypothesis's overlay.
TEST(PairReportInBrowser, PairOutPageOpensAndDrawsTheBestOverlay) {
  FLEETMERGE_REQUIRE_SHARED_MAPS();
  const fs::path dir = testing::MakeTempDir("pair_report_browser");
  const fs::path a = SharedMap("robotis_corridor_run1"), b = SharedMap("robotis_corridor_run3");
  const testing::CommandResult run = testing::Fleetmerge(
      "pair --json " + ShellQuote(a) + " " + ShellQuote(b) + " --out " + ShellQuote(dir / "out"));
  ASSERT_EQ(run.exit_code, 0) << run.both();
  const json printed = json::parse(run.out);
  EXPECT_EQ(printed.at("report_html"), (dir / "out" / "report.html").string());
  const json data = EmbeddedData(testing::ReadFile(dir / "out" / "report.html"));
  ASSERT_TRUE(data.contains("report"));
  const json& pair = data.at("report").at("pairs").at(0);
  EXPECT_EQ(pair.at("hypotheses"), printed.at("hypotheses")) << "the page shows what pair printed";

  const std::optional<fs::path> chromium = Chromium();
  if (!chromium || !FindProgram({"node"})) {
    GTEST_SKIP() << "SKIPPED: no browser test: Chromium or node not found; "
                    "scripts/install_deps.sh installs both";
  }
  const DriverRun browser = Drive(*chromium, dir / "out", dir / "shots",
                                  {{"robotis_corridor_run1", "robotis_corridor_run3"}});
  ASSERT_TRUE(browser.error.empty()) << browser.error;
  ExpectNoConsoleErrorAndNothingFetchedOutside(browser.result, dir / "out");
  EXPECT_EQ(browser.result.at("dom").at("input_maps"),
            json({"robotis_corridor_run1", "robotis_corridor_run3"}));
  ExpectOverlayWhereTheHypothesisPutsIt(browser.result.at("clicks").at(0), pair, 0, dir / "shots",
                                        LoadMap(a), LoadMap(b));
}

// ---- The ring of a map placed by its prior: the page draws it around the map's node (the
// centre of its known cells' box, carried into the merged frame by the map's pose) as a dashed
// circle of radius 11 CSS pixels, 2 wide, in #111, with the map's label above and right.
const Rgb kRingColour(17, 17, 17);

// Centre of the known (not unknown) cells' box of `grid`, in its map frame.
Eigen::Vector2d KnownBoxCentre(const OccupancyGrid& grid) {
  int i0 = grid.width(), j0 = grid.height(), i1 = -1, j1 = -1;
  for (int j = 0; j < grid.height(); ++j) {
    for (int i = 0; i < grid.width(); ++i) {
      if (grid.cells()(j, i) == static_cast<std::uint8_t>(CellState::kUnknown)) continue;
      i0 = std::min(i0, i), i1 = std::max(i1, i + 1), j0 = std::min(j0, j),
      j1 = std::max(j1, j + 1);
    }
  }
  const double r = grid.geometry().resolution_m();
  return grid.geometry().T_map_grid() * Eigen::Vector2d((i0 + i1) * r / 2, (j0 + j1) * r / 2);
}

// Where a point of the merged frame lands in a screenshot of the merged map's viewer: merged
// frame -> preview pixel (column, row from the top, as the preview image is laid out) -> the
// viewer's matrix [a, b, c, d, e, f] (preview pixel -> device pixel of the canvas).
cv::Point2d OnScreen(const Eigen::Vector2d& p_merged, const OccupancyGrid& merged,
                     const json& view) {
  const GridGeometry& g = merged.geometry();
  const Eigen::Vector2d p_grid = g.T_map_grid().inverse() * p_merged;
  const double u = p_grid.x() / g.resolution_m(), v = g.height() - p_grid.y() / g.resolution_m();
  const double m[6] = {view[0], view[1], view[2], view[3], view[4], view[5]};
  return {m[0] * u + m[2] * v + m[4], m[1] * u + m[3] * v + m[5]};
}

// The share of directions around `centre` in which a ring-coloured pixel lies within 3 device
// pixels of `radius_px`. The quarter above and right of the centre is not looked at: the map's
// label (the same #111) is drawn there. Every sampled pixel must be inside the screenshot.
Hits RingCoverage(const cv::Mat3b& shot, const cv::Point2d& centre, double radius_px) {
  Hits hits;
  constexpr int kDirections = 96;
  for (int k = 0; k < kDirections; ++k) {
    const double angle = 2 * M_PI * (k + 0.5) / kDirections;
    const double dx = std::cos(angle), dy = std::sin(angle);  // screen y points down
    if (dx > 0 && dy < 0) continue;
    ++hits.considered;
    bool found = false;
    for (double r = radius_px - 3; r <= radius_px + 3 && !found; r += 0.5) {
      const int x = static_cast<int>(std::floor(centre.x + r * dx));
      const int y = static_cast<int>(std::floor(centre.y + r * dy));
      if (x < 0 || y < 0 || x >= shot.cols || y >= shot.rows) return Hits{};  // not on screen
      found = Near(shot(y, x), kRingColour, 14);
    }
    hits.hits += found;
  }
  return hits;
}

// configs/site_with_priors.yaml, the example job, with its maps' paths made absolute and its
// output in `out`.
std::string SiteWithPriorsJob(const fs::path& out) {
  std::string yaml =
      testing::ReadFile(fs::path(FLEETMERGE_SOURCE_DIR) / "configs" / "site_with_priors.yaml");
  const std::string relative = "../../shared/data/maps/";
  const std::string absolute = testing::SharedMapsDir()->string() + "/";
  int replaced = 0;
  std::size_t at = yaml.find(relative);
  while (at != std::string::npos) {
    yaml.replace(at, relative.size(), absolute);
    ++replaced;
    at = yaml.find(relative, at + absolute.size());
  }
  const std::size_t output = yaml.find("\noutput:");
  if (replaced != 4 || output == std::string::npos) {
    ADD_FAILURE() << "configs/site_with_priors.yaml: expected 4 maps under " << relative
                  << " and an output: line; found " << replaced << " maps";
    return "";
  }
  return yaml.substr(0, output) + "\noutput: " + out.string() + "\n";
}

// The example job of a site map and three robots with known start poses: run4 shares too little
// with the others for any pair, so its prior places it, and the merged map's viewer marks its
// node (and only its node) with a dashed ring.
TEST(PriorPlacedMapInBrowser, IsListedAndRingedWhereItsPosePutsIt) {
  FLEETMERGE_REQUIRE_SHARED_MAPS();
  const fs::path dir = testing::MakeTempDir("prior_report_browser");
  const fs::path out = dir / "out", shots = dir / "shots";
  const std::string job = SiteWithPriorsJob(out);
  ASSERT_FALSE(job.empty());
  testing::WriteFile(dir / "site_with_priors.yaml", job);
  const testing::CommandResult merge =
      testing::Fleetmerge("merge --quiet " + ShellQuote(dir / "site_with_priors.yaml"));
  ASSERT_EQ(merge.exit_code, 0) << merge.both();
  const json report = json::parse(testing::ReadFile(out / "report.json"));

  // report.json: run4 alone is placed by its prior, in a merged component with the others.
  const json& maps = report.at("maps");
  ASSERT_EQ(maps.size(), 4u) << maps.dump();
  int run4 = -1;
  std::vector<int> placed_by_pairs;
  for (int m = 0; m < static_cast<int>(maps.size()); ++m) {
    const std::string name = maps[m].at("name"), placed_by = maps[m].at("placed_by");
    EXPECT_EQ(placed_by == "prior", name == "run4") << name << " placed by " << placed_by;
    if (name == "run4") run4 = m;
    if (placed_by == "pairs") placed_by_pairs.push_back(m);
  }
  ASSERT_GE(run4, 0);
  // Placed by its prior: exactly where its initial_pose says.
  EXPECT_EQ(maps[run4].at("pose"), maps[run4].at("initial_pose"));
  ASSERT_EQ(placed_by_pairs.size(), 2u) << "run2 and run3 pair with the site";
  const int component = maps[run4].at("component");
  json comp;
  for (const json& c : report.at("components")) {
    if (c.at("id") == component) comp = c;
  }
  ASSERT_TRUE(comp.contains("merged_map")) << report.at("components").dump();
  for (const json& m : maps) EXPECT_EQ(m.at("component"), component) << m.dump();

  const std::optional<fs::path> chromium = Chromium();
  if (!chromium || !FindProgram({"node"})) {
    GTEST_SKIP() << "SKIPPED: no browser test: Chromium or node not found; "
                    "scripts/install_deps.sh installs both";
  }
  const DriverRun browser = Drive(*chromium, out, shots, {});
  std::cout << "[ browser  ] site_with_priors report.html opened and checked in " << browser.wall_s
            << " s (Chromium start to exit)\n";
  ASSERT_TRUE(browser.error.empty()) << browser.error;
  ExpectNoConsoleErrorAndNothingFetchedOutside(browser.result, out);

  // The merged map's list says "(placed by prior)" for run4 and for no other map, and run4 is
  // not among the unmerged maps.
  const json& dom = browser.result.at("dom");
  const json* listed = nullptr;
  for (const json& c : dom.at("components")) {
    if (c.at("id") == std::to_string(component)) listed = &c;
  }
  ASSERT_NE(listed, nullptr) << dom.at("components").dump();
  ASSERT_EQ(listed->at("legend").size(), maps.size());
  for (std::size_t k = 0; k < maps.size(); ++k) {
    const std::string name = listed->at("legend")[k], text = listed->at("legend_text")[k];
    EXPECT_EQ(text.find("(placed by prior)") != std::string::npos, name == "run4") << text;
    EXPECT_EQ(text.find("(fixed)") != std::string::npos, name == "site") << text;
  }
  EXPECT_TRUE(dom.at("unmerged").empty()) << dom.at("unmerged").dump();
  // The job's table gives what placed each map and its known pose (the job file's values).
  const json& rows = dom.at("input_rows");
  ASSERT_EQ(rows.size(), 4u) << rows.dump();
  const auto last_two = [&](int m) {
    const json& row = rows.at(m);
    return std::make_pair(row.at(row.size() - 2).get<std::string>(),
                          row.at(row.size() - 1).get<std::string>());
  };
  EXPECT_EQ(last_two(0), std::make_pair(std::string("fixed"), std::string("fixed (its pose)")));
  EXPECT_EQ(last_two(1).first, "pairs");
  EXPECT_EQ(last_two(1).second,
            "initial_pose x 10.300 m, y 4.700 m, yaw -5.73\u00b0 (sigma 0.50 m, 10.0\u00b0)");
  EXPECT_EQ(last_two(3).first, "prior");
  EXPECT_EQ(last_two(3).second,
            "initial_pose x 10.000 m, y 5.000 m, yaw 0.00\u00b0 (sigma 1.00 m, 20.1\u00b0)");

  // The viewer as loaded: the dashed ring around run4's node, where report.json's pose carries
  // the centre of run4's known cells; none around the maps their pairs place; none 1.5 m away.
  const json* seen = nullptr;
  for (const json& v : browser.result.at("component_views")) {
    if (v.at("id") == std::to_string(component)) seen = &v;
  }
  ASSERT_NE(seen, nullptr) << browser.result.at("component_views").dump();
  ASSERT_TRUE(seen->at("view").is_array()) << "the merged map's viewer drew nothing";
  const cv::Mat3b shot = cv::imread((shots / seen->at("screenshot").get<std::string>()).string());
  ASSERT_FALSE(shot.empty());
  const OccupancyGrid merged = LoadMap(out / comp.at("merged_map").get<std::string>()).grid;
  const double ring_px = 11.0 * browser.result.at("device_scale").get<double>();
  const auto node_of = [&](int m) {
    const LoadedMap input = LoadMap(maps[m].at("source").get<std::string>());
    return PoseOf(maps[m].at("pose")) * KnownBoxCentre(input.grid);
  };
  const Eigen::Vector2d run4_node = node_of(run4);
  const Hits ring = RingCoverage(shot, OnScreen(run4_node, merged, seen->at("view")), ring_px);
  std::cout << "[ ring     ] run4's ring: " << ring.hits << " of " << ring.considered
            << " directions\n";
  ASSERT_GT(ring.considered, 0) << "run4's node is not on screen";
  // Dashed (4 on, 3 off): about 4/7 of the directions, neither none nor all.
  EXPECT_GE(ring.fraction(), 0.4) << ring.hits << " of " << ring.considered;
  EXPECT_LE(ring.fraction(), 0.8) << "a solid ring? " << ring.hits << " of " << ring.considered;
  for (int m : placed_by_pairs) {
    const Hits none = RingCoverage(shot, OnScreen(node_of(m), merged, seen->at("view")), ring_px);
    ASSERT_GT(none.considered, 0) << maps[m].at("name") << "'s node is not on screen";
    std::cout << "[ ring     ] around " << maps[m].at("name").get<std::string>() << ": "
              << none.hits << " of " << none.considered << " directions\n";
    EXPECT_LT(none.fraction(), 0.1)
        << "a ring around " << maps[m].at("name") << ": " << none.hits << " of " << none.considered;
  }
  // 1.5 m is about five ring radii here. Not straight right: the label runs there.
  for (const Eigen::Vector2d& offset_m : {Eigen::Vector2d(-1.5, 0), Eigen::Vector2d(0, 1.5),
                                          Eigen::Vector2d(0, -1.5), Eigen::Vector2d(1.5, -1.5)}) {
    const Hits none =
        RingCoverage(shot, OnScreen(run4_node + offset_m, merged, seen->at("view")), ring_px);
    ASSERT_GT(none.considered, 0) << "(" << offset_m.x() << ", " << offset_m.y() << ") m from "
                                  << "run4's node is off screen";
    std::cout << "[ ring     ] (" << offset_m.x() << ", " << offset_m.y()
              << ") m from run4's node: " << none.hits << " of " << none.considered
              << " directions\n";
    EXPECT_LT(none.fraction(), 0.1)
        << "ring pixels (" << offset_m.x() << ", " << offset_m.y()
        << ") m from run4's node: " << none.hits << " of " << none.considered;
  }
}

// The only map with a start pose, in a wing nobody else saw (intel_lab beside two corridor
// runs): placed at its prior in a merged map of its own, so the page lists it with the merged
// maps, "(placed by prior)", and neither among the unmerged maps nor as unmerged in the summary.
TEST(PriorPlacedMapInBrowser, AMapItsPriorPlacesAloneIsNotUnmerged) {
  FLEETMERGE_REQUIRE_SHARED_MAPS();
  const fs::path maps = *testing::SharedMapsDir();
  const fs::path dir = testing::MakeTempDir("lone_prior_report_browser");
  const fs::path out = dir / "out", shots = dir / "shots";
  const testing::CommandResult merge = testing::Fleetmerge(
      "merge --quiet --out " + ShellQuote(out) + " " +
      ShellQuote(maps / "robotis_corridor_run1.yaml") + " " +
      ShellQuote(maps / "robotis_corridor_run2.yaml") + " " + ShellQuote(maps / "intel_lab.yaml") +
      " --initial-pose intel_lab=60,5,0.3");
  ASSERT_EQ(merge.exit_code, 0) << merge.both();
  const json report = json::parse(testing::ReadFile(out / "report.json"));
  ASSERT_EQ(report.at("components").size(), 2u) << report.at("components").dump();
  const json& lab = report.at("maps").at(2);
  ASSERT_EQ(lab.at("placed_by"), "prior") << lab.dump();
  const int component = lab.at("component");

  const std::optional<fs::path> chromium = Chromium();
  if (!chromium || !FindProgram({"node"})) {
    GTEST_SKIP() << "SKIPPED: no browser test: Chromium or node not found; "
                    "scripts/install_deps.sh installs both";
  }
  const DriverRun browser = Drive(*chromium, out, shots, {});
  ASSERT_TRUE(browser.error.empty()) << browser.error;
  ExpectNoConsoleErrorAndNothingFetchedOutside(browser.result, out);
  const json& dom = browser.result.at("dom");
  EXPECT_TRUE(dom.at("unmerged").empty()) << dom.at("unmerged").dump();
  const std::string summary = dom.at("summary");
  EXPECT_NE(summary.find("2 merged map(s)"), std::string::npos) << summary;
  EXPECT_EQ(summary.find("unmerged"), std::string::npos) << summary;
  const json* listed = nullptr;
  for (const json& c : dom.at("components")) {
    if (c.at("id") == std::to_string(component)) listed = &c;
  }
  ASSERT_NE(listed, nullptr) << dom.at("components").dump();
  ASSERT_EQ(listed->at("legend"), json({"intel_lab"}));
  const std::string legend = listed->at("legend_text")[0];
  EXPECT_NE(legend.find("(placed by prior)"), std::string::npos) << legend;
}

// An octree job's page adds each octree's floor plan with its floor height and z offset. The
// octrees are the synthetic pair of `fleetmerge example --octree` (no real octree data ships).
TEST(OctreeReportInBrowser, ShowsEachFloorPlanWithItsZOffset) {
  const fs::path dir = testing::MakeTempDir("octree_report_browser");
  ASSERT_EQ(testing::Fleetmerge("example --octree " + ShellQuote(dir / "case")).exit_code, 0);
  const testing::CommandResult merge =
      testing::Fleetmerge("merge --quiet " + ShellQuote(dir / "case" / "job.yaml"));
  ASSERT_EQ(merge.exit_code, 0) << merge.both();
  const fs::path out = dir / "case" / "merged";
  const json report = json::parse(testing::ReadFile(out / "report.json"));
  const std::optional<fs::path> chromium = Chromium();
  if (!chromium || !FindProgram({"node"})) {
    GTEST_SKIP() << "SKIPPED: no browser test: Chromium or node not found; "
                    "scripts/install_deps.sh installs both";
  }
  const DriverRun browser = Drive(*chromium, out, dir / "shots", {});
  ASSERT_TRUE(browser.error.empty()) << browser.error;
  ExpectNoConsoleErrorAndNothingFetchedOutside(browser.result, out);
  std::vector<std::string> octrees;
  for (const json& m : report.at("maps")) {
    if (m.contains("floor_z")) octrees.push_back(m.at("name"));
  }
  ASSERT_EQ(octrees.size(), 2u) << report.dump();
  EXPECT_EQ(browser.result.at("dom").at("octrees").get<std::vector<std::string>>(), octrees);
  const std::string text = browser.result.at("dom").at("octree_text");
  for (const json& m : report.at("maps")) {
    char line[160];
    std::snprintf(line, sizeof line,
                  "%s: floor at z %.3f m in its own frame; z offset in the merged frame %.3f m",
                  m.at("name").get<std::string>().c_str(), m.at("floor_z").get<double>(),
                  m.at("pose").at("z").get<double>());
    EXPECT_NE(text.find(line), std::string::npos) << line << "\nnot in: " << text;
  }
  EXPECT_NE(text.find("merged_0.bt"), std::string::npos) << text;
}

}  // namespace
}  // namespace fleetmerge
