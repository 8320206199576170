// The `fleetmerge` executable end to end: exit codes, messages, JSON shape, written files.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/fleetmerge_cli.hpp"
#include "tests/support/run_command.hpp"
#include "tests/support/shared_data.hpp"

namespace fleetmerge {
namespace {

using testing::Fleetmerge;

class CliTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new std::filesystem::path(testing::MakeTempDir("cli"));
    ASSERT_EQ(Fleetmerge("example " + (*dir_ / "maps").string()).exit_code, 0);
  }
  static std::string A() { return (*dir_ / "maps" / "robot_a.yaml").string(); }
  static std::string B() { return (*dir_ / "maps" / "robot_b.yaml").string(); }
  static std::filesystem::path* dir_;
};
std::filesystem::path* CliTest::dir_ = nullptr;

TEST_F(CliTest, JsonHasTheDocumentedShapeAndFindsTheTruth) {
  const auto run = Fleetmerge("pair " + A() + " " + B() + " --json -n 3");
  ASSERT_EQ(run.exit_code, 0) << run.both();
  const auto j = nlohmann::json::parse(run.out);
  EXPECT_EQ(j["a"], A());
  EXPECT_EQ(j["b"], B());
  ASSERT_GE(j["hypotheses"].size(), 1u);
  ASSERT_LE(j["hypotheses"].size(), 3u);
  // Best first: no hypothesis beats the first by more than the omega tie (0.01), within which
  // the evidence ranks (core/pose_evidence.hpp); a hypothesis that barely overlaps ranks below
  // every one that overlaps enough, whatever its omega.
  for (const auto& h : j["hypotheses"]) {
    for (const char* key : {"x", "y", "yaw", "omega", "overlap_cells", "wall_agreement"}) {
      ASSERT_TRUE(h.contains(key)) << key;
    }
    EXPECT_LE(h["omega"].get<double>(), j["hypotheses"][0]["omega"].get<double>() + 0.01);
  }
  // The true pose of this pair wins clearly: hypotheses overlap, walls agree, not a coin toss.
  EXPECT_GT(j["hypotheses"][0]["overlap_cells"].get<long>(), 5000);
  EXPECT_GT(j["hypotheses"][0]["wall_agreement"].get<double>(), 0.9);
  ASSERT_TRUE(j["ambiguous"].is_boolean());
  EXPECT_FALSE(j["ambiguous"].get<bool>());
  ASSERT_TRUE(j["margin"].is_number());
  EXPECT_GT(j["margin"].get<double>(), 3.0);
  const YAML::Node truth = YAML::LoadFile((*dir_ / "maps" / "truth.yaml").string())["T_a_b"];
  const auto& best = j["hypotheses"][0];
  EXPECT_NEAR(best["x"].get<double>(), truth["x"].template as<double>(), 0.05);
  EXPECT_NEAR(best["y"].get<double>(), truth["y"].template as<double>(), 0.05);
  EXPECT_NEAR(
      std::remainder(best["yaw"].get<double>() - truth["yaw"].template as<double>(), 2 * M_PI), 0.0,
      0.25 * M_PI / 180);
}

TEST_F(CliTest, TableAndMergedOutput) {
  const auto out = *dir_ / "merged";
  const auto run = Fleetmerge("pair " + A() + " " + B() + " --out " + out.string());
  ASSERT_EQ(run.exit_code, 0) << run.both();
  EXPECT_NE(run.both().find("omega"), std::string::npos);
  EXPECT_NE(run.both().find("merged map: "), std::string::npos);
  EXPECT_TRUE(std::filesystem::exists(out / "merged.yaml"));
  EXPECT_TRUE(std::filesystem::exists(out / "merged.pgm"));
  EXPECT_TRUE(std::filesystem::exists(out / "merged_preview.png"));
  const auto again = Fleetmerge("pair " + A() + " " + B() + " --out " + out.string());
  EXPECT_EQ(again.exit_code, 0) << "re-running into the same folder replaces its results";
}

TEST_F(CliTest, RefusesToOverwriteAnInputMap) {
  // An input named merged.yaml in the output folder must survive.
  const auto folder = *dir_ / "clash";
  std::filesystem::create_directories(folder);
  std::filesystem::copy_file(A(), folder / "merged.yaml");
  std::filesystem::copy_file(*dir_ / "maps" / "robot_a.pgm", folder / "robot_a.pgm");
  const auto before = std::filesystem::file_size(folder / "merged.yaml");
  const auto run = Fleetmerge("pair " + (folder / "merged.yaml").string() + " " + B() + " --out " +
                              folder.string());
  EXPECT_NE(run.exit_code, 0);
  EXPECT_NE(run.both().find("refusing to overwrite"), std::string::npos) << run.both();
  EXPECT_EQ(std::filesystem::file_size(folder / "merged.yaml"), before);
}

TEST_F(CliTest, MissingFileNamesThePath) {
  const auto run = Fleetmerge("pair /nonexistent/a.yaml " + B());
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.both().find("/nonexistent/a.yaml"), std::string::npos) << run.both();
}

TEST_F(CliTest, BadSamplingOptionIsExplained) {
  const auto run = Fleetmerge("pair " + A() + " " + B() + " --hough-sampling random:2");
  EXPECT_NE(run.exit_code, 0);
  EXPECT_NE(run.both().find("--hough-sampling: expected 'all', 'random:F'"), std::string::npos)
      << run.both();
}

// A wrong command line exits 2, whichever check finds it (CLI11's parser or an option's own
// check), for `pair` (the executable) and the other commands (the commands module) alike; a
// failed job or bad input exits 1 (MissingFileNamesThePath); --help and --version exit 0.
TEST_F(CliTest, UsageErrorsExitTwo) {
  const std::vector<std::string> usage_errors = {
      "",                                                        // no command
      "pair " + A(),                                             // a missing map
      "pair " + A() + " " + B() + " -n 0",                       // out of range
      "pair " + A() + " " + B() + " --translation sideways",     // not one of the choices
      "pair " + A() + " " + B() + " --hough-sampling random:2",  // the option's own check
      "pair " + A() + " " + B() + " --bogus",                    // unknown option
      "merge",                                                   // no maps
      "merge --out o " + A() + " --omega-threshold",             // a missing value
      "simulate o --robots 0",
      "frobnicate",  // unknown command
  };
  for (const std::string& args : usage_errors) {
    const auto run = Fleetmerge(args);
    EXPECT_EQ(run.exit_code, 2) << "fleetmerge " << args << "\n" << run.both();
    EXPECT_FALSE(run.err.empty()) << "fleetmerge " << args;
  }
  for (const char* args : {"--help", "--version", "pair --help", "merge --help"}) {
    EXPECT_EQ(Fleetmerge(args).exit_code, 0) << "fleetmerge " << args;
  }
}

TEST_F(CliTest, FreePenaltyIsChecked) {
  const auto bad = Fleetmerge("pair " + A() + " " + B() + " --free-penalty -1");
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.both().find("--free-penalty"), std::string::npos) << bad.both();
  const auto site = Fleetmerge("pair " + A() + " " + B() + " --free-penalty 0.25 --json");
  ASSERT_EQ(site.exit_code, 0) << site.both();
  EXPECT_GE(nlohmann::json::parse(site.out)["hypotheses"].size(), 1u);
}

TEST_F(CliTest, PaperMethodIsSelectable) {
  const auto run =
      Fleetmerge("pair " + A() + " " + B() + " --translation spectra --no-refine --json");
  ASSERT_EQ(run.exit_code, 0) << run.both();
  EXPECT_GE(nlohmann::json::parse(run.out)["hypotheses"].size(), 1u);
}

// The version comes from one place, project(... VERSION x.y.z) in the top CMakeLists.txt, read
// here from the file itself rather than through the build's generated header.
std::string ProjectVersion() {
  std::ifstream in(std::string(FLEETMERGE_SOURCE_DIR) + "/CMakeLists.txt");
  std::stringstream text;
  text << in.rdbuf();
  const std::string cmake = text.str();
  std::smatch match;
  const std::regex project(R"(project\(fleetmerge\s+VERSION\s+([0-9]+\.[0-9]+\.[0-9]+))");
  if (!std::regex_search(cmake, match, project)) return "(no project VERSION in CMakeLists.txt)";
  return match[1];
}

// The process reserves heap address space for huge pages (cli/process_memory.hpp) only where
// that is free: under an address-space limit (ulimit -v) the reservation would leave too little
// for thread stacks, and a merge on two threads failed under 700 MB.
#if defined(__SANITIZE_ADDRESS__)  // GCC
#define FLEETMERGE_TEST_ASAN 1
#elif defined(__has_feature)  // clang
#if __has_feature(address_sanitizer)
#define FLEETMERGE_TEST_ASAN 1
#endif
#endif
TEST_F(CliTest, MergesUnderAnAddressSpaceLimit) {
#if defined(FLEETMERGE_TEST_ASAN)
  GTEST_SKIP() << "AddressSanitizer maps terabytes of shadow memory: no ulimit -v under it";
#else
  const std::filesystem::path out = *dir_ / "limited";
  const auto run = testing::RunCommand("ulimit -v 700000 && " FLEETMERGE_EXECUTABLE
                                       " merge --quiet --threads 2 --out " +
                                       testing::ShellQuote(out) + " " + A() + " " + B());
  EXPECT_EQ(run.exit_code, 0) << run.both();
  EXPECT_TRUE(std::filesystem::exists(out / "report.json"));
#endif
}

TEST(CliVersion, FlagAndCommandPrintTheProjectVersion) {
  const std::string expected = "fleetmerge " + ProjectVersion() + "\n";
  for (const char* args : {"--version", "version"}) {
    const auto run = testing::Fleetmerge(args);
    EXPECT_EQ(run.exit_code, 0) << args << ": " << run.both();
    EXPECT_EQ(run.out, expected) << args;
  }
  // A subcommand is still required otherwise: the version flag did not relax that.
  EXPECT_NE(testing::Fleetmerge("").exit_code, 0);
}

// The executable runs `pair` itself and loads libfleetmerge_commands.so for everything else
// (cli/main.cpp): a copy of the executable alone still pairs, with the same output, and any other
// command names the module it lacks.
TEST_F(CliTest, PairNeedsNoCommandsModuleAndOtherCommandsNameIt) {
  const std::filesystem::path alone = *dir_ / "alone" / "fleetmerge";
  std::filesystem::create_directories(alone.parent_path());
  std::filesystem::copy_file(FLEETMERGE_EXECUTABLE, alone,
                             std::filesystem::copy_options::overwrite_existing);
  const std::string args = " pair " + A() + " " + B() + " --json -n 3";
  const auto with_module = Fleetmerge(args);
  const auto run = testing::RunCommand(testing::ShellQuote(alone) + args);
  ASSERT_EQ(run.exit_code, 0) << run.both();
  EXPECT_EQ(run.out, with_module.out);

  if (std::filesystem::exists(std::filesystem::path(FLEETMERGE_COMMANDS_INSTALL_DIR) /
                              "libfleetmerge_commands.so")) {
    GTEST_SKIP() << "an installed fleetmerge in " FLEETMERGE_COMMANDS_INSTALL_DIR
                    " serves the copy: its missing-module message is not checked";
  }
  const auto version = testing::RunCommand(testing::ShellQuote(alone) + " --version");
  EXPECT_EQ(version.exit_code, 1) << version.both();
  EXPECT_NE(version.err.find("libfleetmerge_commands.so"), std::string::npos) << version.err;
  EXPECT_NE(version.err.find("installation is incomplete"), std::string::npos) << version.err;
  EXPECT_NE(version.err.find(alone.parent_path().string()), std::string::npos) << version.err;
}

// The executable holds its own copy of OpenCV core, from the static archive (cli/CMakeLists.txt):
// it loads neither OpenCV's shared library nor what that library loads (LAPACK, BLAS, the Fortran
// runtime, GLX and X11), and it exports none of OpenCV's symbols, so the commands module and the
// shared OpenCV it loads cannot bind to the executable's copy.
TEST(CliExecutable, HoldsItsOwnOpenCvCoreAndExportsNoneOfIt) {
  if (!FLEETMERGE_STATIC_OPENCV_CORE) {
    GTEST_SKIP() << "OpenCV core's static archive was not found at configure time: the "
                    "executable links the shared library";
  }
  const auto libraries = testing::RunCommand("ldd " FLEETMERGE_EXECUTABLE);
  ASSERT_EQ(libraries.exit_code, 0) << libraries.both();
  for (const char* absent : {"libopencv", "liblapack", "libblas", "libgfortran", "libGLX", "libX11",
                             "libceres", "liboctomap"}) {
    EXPECT_EQ(libraries.out.find(absent), std::string::npos) << absent << " in\n" << libraries.out;
  }
  const auto exported = testing::RunCommand("nm -D --defined-only " FLEETMERGE_EXECUTABLE);
  ASSERT_EQ(exported.exit_code, 0) << exported.both();
  // Itanium mangling: cv:: names hold "N2cv" (nested, also in vtables and typeinfo) or "K2cv".
  std::istringstream lines(exported.out);
  for (std::string line; std::getline(lines, line);) {
    EXPECT_FALSE(std::regex_search(line, std::regex("[NK]2cv|glX"))) << line;
  }
  // That both copies compute the same pair: PairNeedsNoCommandsModuleAndOtherCommandsNameIt.
}

}  // namespace
}  // namespace fleetmerge
