// Every way LoadMap rejects its input: each message must start with the offending file's path
// and name the key or line and what was expected (STYLE.md, "Errors").
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <string>

#include "core/error.hpp"
#include "io/map_io.hpp"
#include "tests/io/io_test_util.hpp"
#include "tests/support/shared_data.hpp"
#include "tests/support/unprivileged.hpp"

namespace fleetmerge {
namespace {

namespace fs = std::filesystem;
namespace ft = fleetmerge::testing;

using ft::Contains;
using ft::StartsWith;

// The message of the fleetmerge::Error LoadMap throws (a test failure if it throws nothing).
std::string LoadError(const fs::path& yaml_path) {
  try {
    LoadMap(yaml_path);
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "LoadMap(" << yaml_path << ") did not throw";
  return "";
}

// A folder holding a valid 3x2 image `tiny.pgm`; each test writes its own map.yaml.
class MapIoErrorsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = ft::MakeTempDir("map_io_errors");
    ft::WriteFile(dir_ / "tiny.pgm", "P2\n3 2\n255\n0 128 254\n205 255 100\n");
  }
  fs::path yaml() const { return dir_ / "map.yaml"; }
  // Writes map.yaml and returns LoadMap's error, checking that it starts with the YAML's path.
  std::string YamlError(const std::string& text) const {
    ft::WriteFile(yaml(), text);
    const std::string message = LoadError(yaml());
    EXPECT_TRUE(StartsWith(message, yaml().string() + ": "));
    return message;
  }
  // A valid YAML with `resolution` and `origin` replaced and `extra` lines appended.
  std::string ErrorWith(const std::string& resolution, const std::string& origin,
                        const std::string& extra = "") const {
    return YamlError("image: tiny.pgm\nresolution: " + resolution + "\norigin: " + origin + "\n" +
                     extra);
  }

  fs::path dir_;
};

TEST_F(MapIoErrorsTest, ValidBaselineLoads) {
  ft::WriteFile(yaml(), "image: tiny.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n");
  EXPECT_NO_THROW(LoadMap(yaml()));
}

// --- The YAML file itself --------------------------------------------------------------------

TEST_F(MapIoErrorsTest, MissingYamlFile) {
  const std::string message = LoadError(dir_ / "nope.yaml");
  EXPECT_TRUE(StartsWith(message, (dir_ / "nope.yaml").string() + ": "));
  EXPECT_TRUE(Contains(message, "No such file or directory"));
}

TEST_F(MapIoErrorsTest, YamlPathIsAFolder) {
  fs::create_directories(dir_ / "folder.yaml");
  const std::string message = LoadError(dir_ / "folder.yaml");
  EXPECT_TRUE(StartsWith(message, (dir_ / "folder.yaml").string() + ": "));
  EXPECT_TRUE(Contains(message, "is a folder"));
}

// As root (CI's fresh machines) the map is loaded as `nobody`: root reads any file.
TEST_F(MapIoErrorsTest, UnreadableYamlFile) {
  const auto user = ft::UserWithoutPrivileges();
  if (!user) GTEST_SKIP() << "running as root on a system without the user nobody";
  ft::WriteFile(yaml(), "image: tiny.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n");
  fs::permissions(yaml(), fs::perms::none);
  const auto message = ft::ErrorAs(*user, yaml(), [&] { LoadMap(yaml()); });
  fs::permissions(yaml(), fs::perms::owner_read | fs::perms::owner_write);
  if (!message) GTEST_SKIP() << "user " << user->uid << " cannot reach " << dir_;
  EXPECT_TRUE(StartsWith(*message, yaml().string() + ": ")) << *message;
  EXPECT_TRUE(Contains(*message, "Permission denied")) << *message;
}

TEST_F(MapIoErrorsTest, YamlPathThroughAFile) {
  ft::WriteFile(dir_ / "plain", "");
  const std::string message = LoadError(dir_ / "plain" / "map.yaml");
  EXPECT_TRUE(StartsWith(message, (dir_ / "plain" / "map.yaml").string() + ": "));
  EXPECT_TRUE(Contains(message, "cannot open map YAML file: Not a directory"));
}

TEST_F(MapIoErrorsTest, MalformedYamlNamesLineAndColumn) {
  const std::string message =
      YamlError("image: tiny.pgm\nresolution: 0.05: 3\norigin: [0, 0, 0]\n");
  EXPECT_TRUE(Contains(message, "line 2, column 17: malformed YAML"));
}

TEST_F(MapIoErrorsTest, UnclosedListNamesLine) {
  const std::string message = YamlError("image: tiny.pgm\norigin: [0, 0, 0\nresolution: 1\n");
  EXPECT_TRUE(Contains(message, "line 3, column 11: malformed YAML"));
}

TEST_F(MapIoErrorsTest, EmptyYaml) {
  EXPECT_TRUE(Contains(YamlError(""), "expected a mapping"));
  EXPECT_TRUE(Contains(YamlError("# only a comment\n"), "got an empty value"));
}

TEST_F(MapIoErrorsTest, YamlNotAMapping) {
  EXPECT_TRUE(Contains(YamlError("- image\n- resolution\n"),
                       "expected a mapping with keys image, resolution, origin, ..., got a list"));
  EXPECT_TRUE(Contains(YamlError("just some text\n"), "got 'just some text'"));
}

TEST_F(MapIoErrorsTest, DuplicateKey) {
  EXPECT_TRUE(Contains(ErrorWith("0.05", "[0, 0, 0]", "resolution: 0.1\n"),
                       "line 4: key 'resolution': appears twice (first at line 2)"));
}

// --- Required keys ---------------------------------------------------------------------------

TEST_F(MapIoErrorsTest, MissingRequiredKeys) {
  EXPECT_TRUE(
      Contains(YamlError("resolution: 0.05\norigin: [0, 0, 0]\n"), "missing required key 'image'"));
  EXPECT_TRUE(Contains(YamlError("image: tiny.pgm\norigin: [0, 0, 0]\n"),
                       "missing required key 'resolution'"));
  EXPECT_TRUE(
      Contains(YamlError("image: tiny.pgm\nresolution: 0.05\n"), "missing required key 'origin'"));
}

// `merge --out DIR job.yaml` reads the job file as a map: say what it is instead.
TEST_F(MapIoErrorsTest, JobFileGivenAsAMap) {
  const std::string error = YamlError("name: site\nmaps:\n  - a.yaml\n  - b.yaml\n");
  EXPECT_TRUE(Contains(error, "missing required key 'image'")) << error;
  EXPECT_TRUE(Contains(error, "as a job file does; run a job file as `fleetmerge merge FILE`"))
      << error;
}

TEST_F(MapIoErrorsTest, ResolutionNotANumber) {
  EXPECT_TRUE(Contains(ErrorWith("abc", "[0, 0, 0]"),
                       "line 2: key 'resolution': expected a number, got 'abc'"));
  EXPECT_TRUE(Contains(ErrorWith("[0.05]", "[0, 0, 0]"),
                       "key 'resolution': expected a number, got a list of 1 element"));
  // An empty value is reported on the key's line, not the next one.
  EXPECT_TRUE(Contains(ErrorWith("", "[0, 0, 0]"),
                       "line 2: key 'resolution': expected a number, got an empty value"));
}

TEST_F(MapIoErrorsTest, ResolutionNotPositiveOrNotFinite) {
  EXPECT_TRUE(Contains(ErrorWith("0", "[0, 0, 0]"), "key 'resolution': expected a number > 0"));
  EXPECT_TRUE(Contains(ErrorWith("-0.05", "[0, 0, 0]"), "got '-0.05'"));
  EXPECT_TRUE(Contains(ErrorWith(".nan", "[0, 0, 0]"),
                       "key 'resolution': expected a finite number, got '.nan'"));
  EXPECT_TRUE(Contains(ErrorWith(".inf", "[0, 0, 0]"),
                       "key 'resolution': expected a finite number, got '.inf'"));
}

TEST_F(MapIoErrorsTest, OriginNotAListOfThree) {
  EXPECT_TRUE(Contains(ErrorWith("0.05", "5"),
                       "line 3: key 'origin': expected a list of 3 numbers [x, y, yaw], got '5'"));
  EXPECT_TRUE(Contains(ErrorWith("0.05", "[1, 2]"), "got a list of 2 elements"));
  EXPECT_TRUE(Contains(ErrorWith("0.05", "[1, 2, 3, 4]"), "got a list of 4 elements"));
  EXPECT_TRUE(Contains(ErrorWith("0.05", "{x: 1, y: 2, yaw: 0}"), "got a mapping"));
}

TEST_F(MapIoErrorsTest, OriginElementNotAFiniteNumber) {
  EXPECT_TRUE(Contains(ErrorWith("0.05", "[0, zero, 0]"),
                       "key 'origin': element 2 (y): expected a number, got 'zero'"));
  EXPECT_TRUE(Contains(ErrorWith("0.05", "[0, 0, .inf]"),
                       "key 'origin': element 3 (yaw): expected a finite number, got '.inf'"));
  EXPECT_TRUE(Contains(ErrorWith("0.05", "[[0], 0, 0]"), "element 1 (x): expected a number"));
}

// --- Optional keys ---------------------------------------------------------------------------

TEST_F(MapIoErrorsTest, NegateNotZeroOrOne) {
  EXPECT_TRUE(Contains(ErrorWith("0.05", "[0, 0, 0]", "negate: 2\n"),
                       "line 4: key 'negate': expected 0 or 1 (or false/true), got '2'"));
  EXPECT_TRUE(Contains(ErrorWith("0.05", "[0, 0, 0]", "negate: maybe\n"), "got 'maybe'"));
}

TEST_F(MapIoErrorsTest, ThresholdNotANumber) {
  EXPECT_TRUE(Contains(ErrorWith("0.05", "[0, 0, 0]", "free_thresh: low\n"),
                       "line 4: key 'free_thresh': expected a number, got 'low'"));
}

TEST_F(MapIoErrorsTest, ThresholdOutOfRange) {
  EXPECT_TRUE(Contains(ErrorWith("0.05", "[0, 0, 0]", "occupied_thresh: 1.5\n"),
                       "key 'occupied_thresh': expected a number in [0, 1], got '1.5'"));
  EXPECT_TRUE(Contains(ErrorWith("0.05", "[0, 0, 0]", "free_thresh: -0.1\n"),
                       "key 'free_thresh': expected a number in [0, 1], got '-0.1'"));
  EXPECT_TRUE(Contains(ErrorWith("0.05", "[0, 0, 0]", "free_thresh: .nan\n"),
                       "key 'free_thresh': expected a finite number"));
}

TEST_F(MapIoErrorsTest, ThresholdsOutOfOrder) {
  EXPECT_TRUE(Contains(
      ErrorWith("0.05", "[0, 0, 0]", "occupied_thresh: 0.6\nfree_thresh: 0.7\n"),
      "line 5: key 'free_thresh': expected free_thresh < occupied_thresh, got free_thresh 0.7 "
      "and occupied_thresh 0.6"));
  EXPECT_TRUE(Contains(ErrorWith("0.05", "[0, 0, 0]", "occupied_thresh: 0.1\n"),
                       "key 'occupied_thresh': expected free_thresh < occupied_thresh"));
  EXPECT_TRUE(Contains(ErrorWith("0.05", "[0, 0, 0]", "occupied_thresh: 0.5\nfree_thresh: 0.5\n"),
                       "expected free_thresh < occupied_thresh"));
}

TEST_F(MapIoErrorsTest, UnknownMode) {
  EXPECT_TRUE(Contains(ErrorWith("0.05", "[0, 0, 0]", "mode: fancy\n"),
                       "line 4: key 'mode': expected trinary, scale or raw, got 'fancy'"));
  EXPECT_TRUE(Contains(ErrorWith("0.05", "[0, 0, 0]", "mode: Trinary\n"), "got 'Trinary'"));
  EXPECT_TRUE(Contains(ErrorWith("0.05", "[0, 0, 0]", "mode: [raw]\n"), "got a list"));
}

// --- The image -------------------------------------------------------------------------------

TEST_F(MapIoErrorsTest, ImageKeyNotAFileName) {
  EXPECT_TRUE(Contains(YamlError("image: ''\nresolution: 0.05\norigin: [0, 0, 0]\n"),
                       "line 1: key 'image': expected an image file name, got ''"));
  EXPECT_TRUE(Contains(YamlError("image: [a.pgm]\nresolution: 0.05\norigin: [0, 0, 0]\n"),
                       "key 'image': expected an image file name, got a list"));
}

TEST_F(MapIoErrorsTest, ImageFileMissing) {
  const std::string message = YamlError("image: nope.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n");
  EXPECT_TRUE(Contains(message, "line 1: key 'image': image file '" + (dir_ / "nope.pgm").string() +
                                    "' does not exist"));
}

TEST_F(MapIoErrorsTest, ImageIsAFolder) {
  fs::create_directories(dir_ / "folder.pgm");
  EXPECT_TRUE(Contains(YamlError("image: folder.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n"),
                       "key 'image': '" + (dir_ / "folder.pgm").string() + "' is a folder"));
}

// Writes `bytes` as the image and returns the error, which must start with the image's path.
std::string ImageError(const fs::path& dir, const std::string& name, const std::string& bytes) {
  ft::WriteFile(dir / name, bytes);
  ft::WriteFile(dir / "map.yaml", ft::MapYaml(name));
  const std::string message = LoadError(dir / "map.yaml");
  EXPECT_TRUE(StartsWith(message, (dir / name).string() + ": "));
  EXPECT_TRUE(Contains(message, "(the image of map " + (dir / "map.yaml").string() + ")"));
  return message;
}

TEST_F(MapIoErrorsTest, ImageNotAnImage) {
  // Refused by their magic bytes, before any decoder sees them.
  EXPECT_TRUE(Contains(ImageError(dir_, "fake.pgm", "hello, I am text\n"),
                       "is not a PGM or PNG image (it starts with bytes 68 65 6c 6c 6f 2c 20 49)"));
  EXPECT_TRUE(
      Contains(ImageError(dir_, "fake.png", "not a png at all"), "is not a PGM or PNG image"));
}

TEST_F(MapIoErrorsTest, TruncatedImages) {
  EXPECT_TRUE(Contains(ImageError(dir_, "short.pgm", "P5\n4 4\n255\n\x01\x02"),
                       "is truncated: its header announces 4 x 4 pixels (16 bytes of pixel data) "
                       "but only 2 bytes follow it"));
  const std::string png = ft::ReadFile(ft::FixtureDir() / "tiny_grey_alpha.png");
  EXPECT_TRUE(Contains(ImageError(dir_, "short.png", png.substr(0, 40)),
                       "is not a readable PGM/PNG image"));
}

TEST_F(MapIoErrorsTest, EmptyImages) {
  EXPECT_TRUE(Contains(ImageError(dir_, "zero.pgm", ""), "is empty (0 bytes)"));
  EXPECT_TRUE(
      Contains(ImageError(dir_, "none.pgm", "P5\n0 0\n255\n"), "is an empty image (0 x 0 pixels)"));
  EXPECT_TRUE(
      Contains(ImageError(dir_, "flat.pgm", "P2\n3 0\n255\n"), "is an empty image (3 x 0 pixels)"));
}

TEST_F(MapIoErrorsTest, OtherFormatsRefusedByMagic) {
  // A one-pixel grey Portable FloatMap (OpenCV would decode it as 32-bit float): only Netpbm
  // and PNG reach a decoder.
  const std::string pfm = std::string("Pf\n1 1\n-1.0\n") + std::string("\x00\x00\x00\x3f", 4);
  EXPECT_TRUE(Contains(ImageError(dir_, "float.pfm", pfm),
                       "is not a PGM or PNG image (it starts with bytes 50 66"));
}

TEST_F(MapIoErrorsTest, CellLimitBeforeDecoding) {
  // 3 x 2 pixels: loads with a limit of 6 cells, refused with 5, naming the limit's knobs.
  ft::WriteFile(dir_ / "small.pgm", "P5\n3 2\n255\n" + std::string(6, '\xfe'));
  ft::WriteFile(dir_ / "small.yaml", ft::MapYaml("small.pgm"));
  EXPECT_EQ(LoadMap(dir_ / "small.yaml", 6).grid.width(), 3);
  try {
    LoadMap(dir_ / "small.yaml", 5);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_TRUE(Contains(e.what(),
                         "small.pgm: is 3 x 2 = 6 cells, more than the limit of 5 cells "
                         "(raise it with --max-map-cells or the job key max_map_cells)"));
  }
}

}  // namespace
}  // namespace fleetmerge
