// LoadMap / SaveMap on tiny maps whose cells are written out below. Grids are rendered top row
// first ('#' occupied, '.' free, '?' unknown), i.e. in the same order as the image pixels.
#include "io/map_io.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <random>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "tests/io/io_test_util.hpp"
#include "tests/support/shared_data.hpp"

namespace fleetmerge {
namespace {

namespace fs = std::filesystem;
namespace ft = fleetmerge::testing;
using Rows = std::vector<std::string>;
constexpr double kPi = 3.14159265358979323846;

// Writes `image_bytes` as `image_name` and a YAML naming it, then loads the map.
LoadedMap LoadGenerated(const std::string& test, const std::string& image_name,
                        const std::string& image_bytes, const std::string& yaml_extra = "") {
  const fs::path dir = ft::MakeTempDir(test);
  ft::WriteFile(dir / image_name, image_bytes);
  ft::WriteFile(dir / "map.yaml", ft::MapYaml(image_name, yaml_extra));
  return LoadMap(dir / "map.yaml");
}

// Writes an image with cv::imwrite (for formats built in-test) and loads it with a YAML.
LoadedMap LoadWritten(const std::string& test, const std::string& image_name, const cv::Mat& image,
                      const std::string& yaml_extra = "") {
  const fs::path dir = ft::MakeTempDir(test);
  EXPECT_TRUE(cv::imwrite((dir / image_name).string(), image));
  ft::WriteFile(dir / "map.yaml", ft::MapYaml(image_name, yaml_extra));
  return LoadMap(dir / "map.yaml");
}

void ExpectSameMap(const OccupancyGrid& a, const OccupancyGrid& b) {
  ASSERT_EQ(a.width(), b.width());
  ASSERT_EQ(a.height(), b.height());
  EXPECT_EQ(cv::countNonZero(a.cells() != b.cells()), 0);
  EXPECT_EQ(a.geometry().resolution_m(), b.geometry().resolution_m());
  EXPECT_EQ(a.geometry().T_map_grid().x_m(), b.geometry().T_map_grid().x_m());
  EXPECT_EQ(a.geometry().T_map_grid().y_m(), b.geometry().T_map_grid().y_m());
  EXPECT_EQ(a.geometry().T_map_grid().yaw_rad(), b.geometry().T_map_grid().yaw_rad());
}

// --- Checked-in fixtures (tests/data/maps, pixels listed in its README.md) -------------------

TEST(MapIoTest, BinaryPgmFixtureCellsAndOrientation) {
  const LoadedMap map = LoadMap(ft::FixtureDir() / "tiny_p5.yaml");
  ASSERT_EQ(map.grid.width(), 4);
  ASSERT_EQ(map.grid.height(), 3);
  // Pixels 0 254 205 254 / 254 254 0 205 / 205 0 254 254 (top row first).
  EXPECT_EQ(ft::RenderTopFirst(map.grid), (Rows{"#.?.", "..#?", "?#.."}));
  // Image row 0 is the top of the map: image pixel (0, 0) is cell (0, height - 1) and the
  // bottom-left pixel (value 205) is cell (0, 0), stored in cells()(0, 0).
  EXPECT_EQ(map.grid.at({0, 2}), CellState::kOccupied);
  EXPECT_EQ(map.grid.at({0, 0}), CellState::kUnknown);
  EXPECT_EQ(map.grid.at({1, 0}), CellState::kOccupied);
  EXPECT_EQ(map.grid.cells()(0, 1), static_cast<std::uint8_t>(CellState::kOccupied));
  EXPECT_EQ(map.grid.at({3, 1}), CellState::kUnknown);
}

TEST(MapIoTest, BinaryPgmFixtureGeometryAndMetadata) {
  const LoadedMap map = LoadMap(ft::FixtureDir() / "tiny_p5.yaml");
  const GridGeometry& geometry = map.grid.geometry();
  EXPECT_DOUBLE_EQ(geometry.resolution_m(), 0.1);
  EXPECT_DOUBLE_EQ(geometry.T_map_grid().x_m(), 1.0);
  EXPECT_DOUBLE_EQ(geometry.T_map_grid().y_m(), -2.0);
  EXPECT_DOUBLE_EQ(geometry.T_map_grid().yaw_rad(), 0.5);
  EXPECT_EQ(map.metadata.yaml_path, ft::FixtureDir() / "tiny_p5.yaml");
  EXPECT_EQ(map.metadata.image_path, ft::FixtureDir() / "tiny_p5.pgm");
  EXPECT_DOUBLE_EQ(map.metadata.resolution_m, 0.1);
  EXPECT_FALSE(map.metadata.negate);
  EXPECT_DOUBLE_EQ(map.metadata.occupied_thresh, 0.65);
  EXPECT_DOUBLE_EQ(map.metadata.free_thresh, 0.196);
  EXPECT_EQ(map.metadata.mode, MapMode::kTrinary);
}

TEST(MapIoTest, AsciiPgmFixture) {
  const LoadedMap map = LoadMap(ft::FixtureDir() / "tiny_p2.yaml");
  // Pixels 0 128 254 / 205 255 100: p = (255 - v) / 255 = 1, .50, .004 / .196, 0, .61.
  EXPECT_EQ(ft::RenderTopFirst(map.grid), (Rows{"#?.", "?.?"}));
}

TEST(MapIoTest, SixteenBitPgmFixtureIsScaledBy257) {
  const LoadedMap map = LoadMap(ft::FixtureDir() / "tiny_16bit.yaml");
  // Pixels 65535 0 52685 / 65278 32768 0 -> v / 257 = 255 0 205 / 254 127.5 0.
  EXPECT_EQ(ft::RenderTopFirst(map.grid), (Rows{".#?", ".?#"}));
}

TEST(MapIoTest, GreyAlphaPngFixtureTransparentIsUnknown) {
  const LoadedMap map = LoadMap(ft::FixtureDir() / "tiny_grey_alpha.yaml");
  // (grey, alpha): (0,255) (0,0) (254,255) / (254,0) (205,255) (254,128).
  EXPECT_EQ(ft::RenderTopFirst(map.grid), (Rows{"#?.", "??."}));
}

TEST(MapIoTest, AbsoluteImagePathAndRawModeIgnoresAlpha) {
  const fs::path dir = ft::MakeTempDir("map_io_absolute");
  const fs::path image = fs::absolute(ft::FixtureDir() / "tiny_grey_alpha.png");
  ft::WriteFile(dir / "map.yaml", ft::MapYaml(image.string(), "mode: raw\n"));
  const LoadedMap map = LoadMap(dir / "map.yaml");
  EXPECT_EQ(map.metadata.image_path, image);
  // Raw: 0 -> 0 % (free, even where alpha is 0); 205 and 254 are > 100 -> unknown.
  EXPECT_EQ(ft::RenderTopFirst(map.grid), (Rows{"..?", "???"}));
}

TEST(MapIoTest, ScaleModeHonoursAlphaLikeTrinary) {
  const fs::path dir = ft::MakeTempDir("map_io_scale_alpha");
  const fs::path image = fs::absolute(ft::FixtureDir() / "tiny_grey_alpha.png");
  ft::WriteFile(dir / "map.yaml", ft::MapYaml(image.string(), "mode: scale\n"));
  EXPECT_EQ(ft::RenderTopFirst(LoadMap(dir / "map.yaml").grid), (Rows{"#?.", "??."}));
}

TEST(MapIoTest, ImagePathRelativeToYamlFolder) {
  const fs::path dir = ft::MakeTempDir("map_io_relative");
  fs::create_directories(dir / "maps");
  fs::create_directories(dir / "images");
  fs::copy_file(ft::FixtureDir() / "tiny_p5.pgm", dir / "images" / "m.pgm");
  ft::WriteFile(dir / "maps" / "m.yaml", ft::MapYaml("../images/m.pgm"));
  const LoadedMap map = LoadMap(dir / "maps" / "m.yaml");
  EXPECT_TRUE(fs::equivalent(map.metadata.image_path, dir / "images" / "m.pgm"));
  EXPECT_EQ(ft::RenderTopFirst(map.grid), (Rows{"#.?.", "..#?", "?#.."}));
}

// --- Formats generated in-test ---------------------------------------------------------------

TEST(MapIoTest, RgbPngUsesMeanOfChannels) {
  // BGR pixels: black, near white, pure blue (mean 85), pure red (mean 85), yellow (mean 170).
  // Any single channel would make blue or red free; their mean (p = 0.67) is occupied.
  cv::Mat3b image(1, 5);
  image << cv::Vec3b(0, 0, 0), cv::Vec3b(254, 254, 254), cv::Vec3b(255, 0, 0), cv::Vec3b(0, 0, 255),
      cv::Vec3b(0, 255, 255);
  EXPECT_EQ(ft::RenderTopFirst(LoadWritten("map_io_rgb", "m.png", image).grid), (Rows{"#.##?"}));
}

TEST(MapIoTest, RgbaPngTransparentIsUnknown) {
  cv::Mat4b image(1, 4);
  image << cv::Vec4b(0, 0, 0, 255), cv::Vec4b(0, 0, 0, 0), cv::Vec4b(254, 254, 254, 1),
      cv::Vec4b(254, 254, 254, 0);
  EXPECT_EQ(ft::RenderTopFirst(LoadWritten("map_io_rgba", "m.png", image).grid), (Rows{"#?.?"}));
}

TEST(MapIoTest, SixteenBitPngIsScaledBy257) {
  cv::Mat_<std::uint16_t> image(1, 4);
  image << 0, 65535, 205 * 257, 254 * 257;
  EXPECT_EQ(ft::RenderTopFirst(LoadWritten("map_io_png16", "m.png", image).grid), (Rows{"#.?."}));
}

TEST(MapIoTest, SixteenBitAsciiPgmIsScaledByItsMaxval) {
  // OpenCV returns 16-bit PGM samples raw (0..1000 here); the loader divides by maxval.
  const LoadedMap map = LoadGenerated("map_io_p2_16", "m.pgm", "P2\n3 1\n1000\n0 1000 500\n");
  EXPECT_EQ(ft::RenderTopFirst(map.grid), (Rows{"#.?"}));
}

TEST(MapIoTest, EightBitPgmWithSmallMaxval) {
  const LoadedMap map = LoadGenerated("map_io_p2_100", "m.pgm", "P2\n3 1\n100\n0 100 50\n");
  EXPECT_EQ(ft::RenderTopFirst(map.grid), (Rows{"#.?"}));
}

TEST(MapIoTest, BinaryPgmWithSmallMaxvalIsRescaledToo) {
  // maxval is white in binary files as in ASCII ones (OpenCV, the former decoder, returned
  // binary samples raw, so 100 read as dark grey: occupied).
  const LoadedMap map =
      LoadGenerated("map_io_p5_100", "m.pgm", std::string("P5\n3 1\n100\n\x00\x64\x32", 14));
  EXPECT_EQ(ft::RenderTopFirst(map.grid), (Rows{"#.?"}));
}

TEST(MapIoTest, ExactBytesOfA3x2AsciiPgm) {
  const LoadedMap map = LoadGenerated("map_io_p2_exact", "m.pgm",
                                      "P2\n# a comment\n3 2\n255\n254 254 0\n0 205 254\n");
  EXPECT_EQ(ft::RenderTopFirst(map.grid), (Rows{"..#", "#?."}));
  EXPECT_EQ(map.grid.at({2, 1}), CellState::kOccupied);  // image pixel (2, 0): the top row
}

// --- Conversion rules ------------------------------------------------------------------------

const char* const kGreyRamp = "P2\n5 1\n255\n0 64 128 192 255\n";  // p = 1 .749 .498 .247 0

TEST(MapIoTest, DefaultThresholds) {
  EXPECT_EQ(ft::RenderTopFirst(LoadGenerated("map_io_ramp", "m.pgm", kGreyRamp).grid),
            (Rows{"##??."}));
}

TEST(MapIoTest, NegateInvertsShades) {
  for (const char* negate : {"negate: 1\n", "negate: true\n"}) {
    const LoadedMap map = LoadGenerated("map_io_negate", "m.pgm", kGreyRamp, negate);
    EXPECT_TRUE(map.metadata.negate);
    EXPECT_EQ(ft::RenderTopFirst(map.grid), (Rows{".??##"})) << negate;
  }
  EXPECT_FALSE(
      LoadGenerated("map_io_negate0", "m.pgm", kGreyRamp, "negate: false\n").metadata.negate);
}

TEST(MapIoTest, ThresholdsFromYaml) {
  const LoadedMap map = LoadGenerated("map_io_thresh", "m.pgm", kGreyRamp,
                                      "occupied_thresh: 0.4\nfree_thresh: 0.3\n");
  EXPECT_DOUBLE_EQ(map.metadata.occupied_thresh, 0.4);
  EXPECT_DOUBLE_EQ(map.metadata.free_thresh, 0.3);
  EXPECT_EQ(ft::RenderTopFirst(map.grid), (Rows{"###.."}));
}

TEST(MapIoTest, ThresholdsAreStrict) {
  // p > occupied_thresh and p < free_thresh: p = 1 with occupied_thresh 1 is not occupied.
  const LoadedMap map =
      LoadGenerated("map_io_strict", "m.pgm", kGreyRamp, "occupied_thresh: 1\nfree_thresh: 0\n");
  EXPECT_EQ(ft::RenderTopFirst(map.grid), (Rows{"?????"}));
}

TEST(MapIoTest, ScaleModeWithoutAlphaMatchesTrinary) {
  const LoadedMap map = LoadGenerated("map_io_scale", "m.pgm", kGreyRamp, "mode: scale\n");
  EXPECT_EQ(map.metadata.mode, MapMode::kScale);
  EXPECT_EQ(ft::RenderTopFirst(map.grid), (Rows{"##??."}));
}

TEST(MapIoTest, RawModeReadsPercentages) {
  const std::string image = "P2\n8 1\n255\n0 19 20 65 66 100 101 255\n";
  for (const char* negate : {"negate: 0\n", "negate: 1\n"}) {  // raw ignores negate (Nav2)
    const LoadedMap map =
        LoadGenerated("map_io_raw", "m.pgm", image, std::string("mode: raw\n") + negate);
    EXPECT_EQ(map.metadata.mode, MapMode::kRaw);
    EXPECT_EQ(ft::RenderTopFirst(map.grid), (Rows{"..??##??"})) << negate;
  }
}

TEST(MapIoTest, MissingOptionalKeysTakeDefaultsAndUnknownKeysAreIgnored) {
  const LoadedMap map = LoadGenerated("map_io_defaults", "m.pgm", kGreyRamp,
                                      "comment: made by hand\nextra: [1, 2, {a: b}]\n");
  EXPECT_FALSE(map.metadata.negate);
  EXPECT_DOUBLE_EQ(map.metadata.occupied_thresh, 0.65);
  EXPECT_DOUBLE_EQ(map.metadata.free_thresh, 0.196);
  EXPECT_EQ(map.metadata.mode, MapMode::kTrinary);
}

TEST(MapIoTest, OriginYawIsHonoured) {
  const fs::path dir = ft::MakeTempDir("map_io_yaw");
  fs::copy_file(ft::FixtureDir() / "tiny_p2.pgm", dir / "m.pgm");
  ft::WriteFile(dir / "map.yaml",
                "image: m.pgm\nresolution: 0.1\norigin: [1.0, 2.0, 1.5707963267948966]\n");
  const GridGeometry geometry = LoadMap(dir / "map.yaml").grid.geometry();
  EXPECT_DOUBLE_EQ(geometry.T_map_grid().yaw_rad(), kPi / 2);
  // Cell (0, 0)'s centre is (0.05, 0.05) in the grid frame, rotated by 90 degrees.
  EXPECT_NEAR(geometry.CellCenter({0, 0}).x(), 0.95, 1e-12);
  EXPECT_NEAR(geometry.CellCenter({0, 0}).y(), 2.05, 1e-12);
  EXPECT_NEAR(geometry.CellCenter({2, 0}).y(), 2.25, 1e-12);
}

// --- Saving and round trips ------------------------------------------------------------------

TEST(MapIoTest, SaveWritesTrinaryPgmAndYaml) {
  const LoadedMap map = LoadMap(ft::FixtureDir() / "tiny_p5.yaml");
  const fs::path dir = ft::MakeTempDir("map_io_save");
  SaveMap(map.grid, dir / "out.yaml");
  EXPECT_EQ(ft::FileNames(dir), (std::vector<std::string>{"out.pgm", "out.yaml"}));
  EXPECT_EQ(ft::ReadFile(dir / "out.yaml"),
            "image: out.pgm\nresolution: 0.1\norigin: [1, -2, 0.5]\nnegate: 0\n"
            "occupied_thresh: 0.65\nfree_thresh: 0.196\nmode: trinary\n");
  // The fixture is already trinary 0/205/254, so the saved pixels equal it, rows unflipped.
  const std::string pgm = ft::ReadFile(dir / "out.pgm");
  EXPECT_EQ(pgm.substr(0, 2), "P5");
  const cv::Mat saved = cv::imread((dir / "out.pgm").string(), cv::IMREAD_UNCHANGED);
  const cv::Mat fixture =
      cv::imread((ft::FixtureDir() / "tiny_p5.pgm").string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(saved.type(), CV_8UC1);
  EXPECT_EQ(cv::norm(saved, fixture, cv::NORM_INF), 0.0);
}

TEST(MapIoTest, FixturesRoundTrip) {
  for (const char* name : {"tiny_p5", "tiny_p2", "tiny_16bit", "tiny_grey_alpha"}) {
    const LoadedMap original = LoadMap(ft::FixtureDir() / (std::string(name) + ".yaml"));
    const fs::path dir = ft::MakeTempDir("map_io_round_trip");
    SaveMap(original.grid, dir / "copy.yaml");
    ExpectSameMap(LoadMap(dir / "copy.yaml").grid, original.grid);
  }
}

TEST(MapIoTest, RandomGridsRoundTripExactly) {
  std::mt19937 rng(20240611);
  std::uniform_int_distribution<int> size(1, 40);
  std::uniform_int_distribution<int> state(0, 2);
  std::uniform_real_distribution<double> xy(-100.0, 100.0);
  std::uniform_real_distribution<double> yaw(-kPi, kPi);
  std::uniform_real_distribution<double> resolution(0.01, 0.2);
  const std::vector<double> special_yaws = {0.0, kPi, -kPi + 1e-9, 1e-8, -1e-8};
  const fs::path dir = ft::MakeTempDir("map_io_random");
  for (int trial = 0; trial < 30; ++trial) {
    const double yaw_rad =
        trial < static_cast<int>(special_yaws.size()) ? special_yaws[trial] : yaw(rng);
    const GridGeometry geometry(resolution(rng), {size(rng), size(rng)},
                                Pose2(xy(rng), xy(rng), yaw_rad));
    OccupancyGrid grid(geometry);
    for (int j = 0; j < grid.height(); ++j) {
      for (int i = 0; i < grid.width(); ++i) grid.set({i, j}, static_cast<CellState>(state(rng)));
    }
    SaveMap(grid, dir / "random.yaml");
    ExpectSameMap(LoadMap(dir / "random.yaml").grid, grid);
  }
  EXPECT_EQ(ft::FileNames(dir), (std::vector<std::string>{"random.pgm", "random.yaml"}));
}

TEST(MapIoTest, OddFileNamesAreQuotedInTheYaml) {
  const LoadedMap original = LoadMap(ft::FixtureDir() / "tiny_p5.yaml");
  const fs::path dir = ft::MakeTempDir("map_io_odd_name");
  SaveMap(original.grid, dir / "odd #name: \"x\".yaml");
  const LoadedMap copy = LoadMap(dir / "odd #name: \"x\".yaml");
  EXPECT_EQ(copy.metadata.image_path.filename(), "odd #name: \"x\".pgm");
  ExpectSameMap(copy.grid, original.grid);
}

TEST(MapIoTest, SaveRefusesProtectedInputsAndWritesNothing) {
  const fs::path dir = ft::MakeTempDir("map_io_protect");
  fs::copy_file(ft::FixtureDir() / "tiny_p5.pgm", dir / "in.pgm");
  ft::WriteFile(dir / "in.yaml", ft::MapYaml("in.pgm"));
  const std::string yaml_before = ft::ReadFile(dir / "in.yaml");
  const std::string pgm_before = ft::ReadFile(dir / "in.pgm");
  const LoadedMap map = LoadMap(dir / "in.yaml");
  EXPECT_THROW(SaveMap(map.grid, dir / "in.yaml", {dir / "in.yaml"}), Error);
  EXPECT_EQ(ft::ReadFile(dir / "in.yaml"), yaml_before);
  // Protecting only the image still blocks the YAML beside it (both are checked first).
  fs::remove(dir / "in.yaml");
  try {
    SaveMap(map.grid, dir / "in.yaml", {dir / "in.pgm"});
    ADD_FAILURE() << "SaveMap overwrote a protected image";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("refusing to overwrite input file"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("in.pgm"), std::string::npos);
  }
  EXPECT_FALSE(fs::exists(dir / "in.yaml"));
  EXPECT_EQ(ft::ReadFile(dir / "in.pgm"), pgm_before);
  EXPECT_EQ(ft::FileNames(dir), (std::vector<std::string>{"in.pgm"}));
}

TEST(MapIoTest, SaveRejectsBadTargetsAndGrids) {
  const fs::path dir = ft::MakeTempDir("map_io_save_bad");
  OccupancyGrid grid(GridGeometry(0.05, {3, 2}));
  EXPECT_THROW(SaveMap(grid, dir / "map.pgm"), Error);  // the image would be the YAML itself
  EXPECT_THROW(SaveMap(OccupancyGrid(GridGeometry(0.05, {0, 0})), dir / "empty.yaml"), Error);
  grid.mutable_cells()(1, 2) = 7;
  try {
    SaveMap(grid, dir / "bad.yaml");
    ADD_FAILURE() << "SaveMap accepted a cell value of 7";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind((dir / "bad.yaml").string(), 0), 0u) << message;
    EXPECT_NE(message.find("cell (2, 1) holds 7"), std::string::npos) << message;
  }
  EXPECT_TRUE(ft::FileNames(dir).empty());
}

TEST(MapIoTest, SaveIntoMissingFolderNamesThePath) {
  const fs::path target = ft::MakeTempDir("map_io_save_missing") / "no_such_folder" / "m.yaml";
  try {
    SaveMap(OccupancyGrid(GridGeometry(0.05, {2, 2})), target);
    ADD_FAILURE() << "SaveMap wrote into a missing folder";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no_such_folder"), std::string::npos) << e.what();
  }
}

TEST(MapIoTest, SaveImageWritesPngAndPgm) {
  const fs::path dir = ft::MakeTempDir("map_io_save_image");
  cv::Mat3b colour(2, 3, cv::Vec3b(10, 20, 30));
  colour(1, 2) = cv::Vec3b(200, 100, 0);
  SaveImage(colour, dir / "preview.png");
  const cv::Mat colour_back = cv::imread((dir / "preview.png").string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(colour_back.type(), CV_8UC3);
  EXPECT_EQ(cv::norm(colour_back, colour, cv::NORM_INF), 0.0);

  cv::Mat_<std::uint16_t> deep(2, 2);
  deep << 0, 1000, 65535, 7;
  SaveImage(deep, dir / "deep.PGM");
  const cv::Mat deep_back = cv::imread((dir / "deep.PGM").string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(deep_back.type(), CV_16UC1);
  EXPECT_EQ(cv::norm(deep_back, deep, cv::NORM_INF), 0.0);
  EXPECT_EQ(ft::FileNames(dir), (std::vector<std::string>{"deep.PGM", "preview.png"}));
}

TEST(MapIoTest, SaveImageRejectsUnsupportedRequests) {
  const fs::path dir = ft::MakeTempDir("map_io_save_image_bad");
  const cv::Mat3b colour(2, 2, cv::Vec3b(1, 2, 3));
  EXPECT_THROW(SaveImage(colour, dir / "x.jpg"), Error);
  EXPECT_THROW(SaveImage(colour, dir / "x.pgm"), Error);  // PGM is single-channel
  EXPECT_THROW(SaveImage(cv::Mat(), dir / "x.png"), Error);
  EXPECT_THROW(SaveImage(cv::Mat1f(2, 2, 0.5f), dir / "x.png"), Error);
  SaveImage(colour, dir / "keep.png");
  const std::string before = ft::ReadFile(dir / "keep.png");
  EXPECT_THROW(SaveImage(cv::Mat3b(1, 1), dir / "keep.png", {dir / "keep.png"}), Error);
  EXPECT_EQ(ft::ReadFile(dir / "keep.png"), before);
  EXPECT_EQ(ft::FileNames(dir), (std::vector<std::string>{"keep.png"}));
}

}  // namespace
}  // namespace fleetmerge
