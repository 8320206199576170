// `fleetmerge merge` on degenerate and hostile jobs, end to end: a one-map job (its map is the
// merged map), maps with no occupied cell / all unknown / 1 x 1 cell beside a real pair, the
// cell limit from the command line and the job file, and output folders that hold another job's
// results or files fleetmerge did not write (one job's refusal does not stop the others).
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "io/map_io.hpp"
#include "tests/support/files.hpp"
#include "tests/support/fleetmerge_cli.hpp"
#include "tests/support/run_command.hpp"
#include "tests/support/shared_data.hpp"

namespace fleetmerge {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using testing::ShellQuote;

using testing::Fleetmerge;
using testing::ReadFile;
using testing::WriteFile;

// A map `name`.yaml/.pgm in `dir`: width x height pixels of one grey value.
fs::path FlatMap(const fs::path& dir, const std::string& name, int width, int height,
                 unsigned char grey) {
  WriteFile(dir / (name + ".pgm"), "P5\n" + std::to_string(width) + " " + std::to_string(height) +
                                       "\n255\n" + std::string(width * height, char(grey)));
  WriteFile(dir / (name + ".yaml"),
            "image: " + name + ".pgm\nresolution: 0.05\norigin: [1.0, 2.0, 0.0]\n");
  return dir / (name + ".yaml");
}

class MergeHardeningTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = testing::MakeTempDir("merge_hardening");
    ASSERT_EQ(Fleetmerge("example " + ShellQuote(dir_ / "ex")).exit_code, 0);
  }
  fs::path A() const { return dir_ / "ex" / "robot_a.yaml"; }
  fs::path B() const { return dir_ / "ex" / "robot_b.yaml"; }
  fs::path dir_;
};

TEST_F(MergeHardeningTest, OneMapJobWritesThatMapAsTheMergedMap) {
  for (const auto& [name, grey] : {std::pair<std::string, int>{"all_unknown", 205}, {"one", -1}}) {
    const fs::path input =
        grey < 0 ? FlatMap(dir_, name, 1, 1, 0) : FlatMap(dir_, name, 30, 20, 205);
    const fs::path out = dir_ / ("out_" + name);
    const auto run = Fleetmerge("merge --quiet --out " + ShellQuote(out) + " " + ShellQuote(input));
    ASSERT_EQ(run.exit_code, 0) << run.both();
    const LoadedMap original = LoadMap(input), merged = LoadMap(out / "merged_0.yaml");
    EXPECT_EQ(cv::countNonZero(original.grid.cells() != merged.grid.cells()), 0) << name;
    EXPECT_EQ(merged.grid.width(), original.grid.width());
    EXPECT_NEAR(merged.metadata.origin.x_m(), 1.0, 1e-9);
    const json report = json::parse(ReadFile(out / "report.json"));
    EXPECT_EQ(report["components"][0]["merged_map"], "merged_0.yaml") << report;
  }
}

TEST_F(MergeHardeningTest, DegenerateMapsStayUnmergedBesideARealPair) {
  const fs::path out = dir_ / "out";
  const auto run =
      Fleetmerge("merge --quiet --out " + ShellQuote(out) + " " + ShellQuote(A()) + " " +
                 ShellQuote(B()) + " " + ShellQuote(FlatMap(dir_, "free_only", 40, 30, 254)) + " " +
                 ShellQuote(FlatMap(dir_, "unknown_only", 40, 30, 205)) + " " +
                 ShellQuote(FlatMap(dir_, "single_cell", 1, 1, 0)));
  ASSERT_EQ(run.exit_code, 0) << run.both();
  const json report = json::parse(ReadFile(out / "report.json"));
  ASSERT_EQ(report["components"].size(), 4u) << report;
  EXPECT_EQ(report["components"][0]["maps"], json({"robot_a", "robot_b"}));
  EXPECT_TRUE(fs::exists(out / "merged_0.yaml"));
  for (const json& pair : report["pairs"]) {
    if (pair["b"] == "robot_b") continue;
    EXPECT_FALSE(pair["accepted"].get<bool>()) << pair;
  }
}

TEST_F(MergeHardeningTest, CellLimitFromCommandLineAndJobFile) {
  // robot_a is 600 x 276 = 165600 cells.
  auto run = Fleetmerge("merge --quiet --max-map-cells 100000 --out " + ShellQuote(dir_ / "o") +
                        " " + ShellQuote(A()) + " " + ShellQuote(B()));
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("more than the limit of 100000 cells (raise it with --max-map-cells"),
            std::string::npos)
      << run.err;
  EXPECT_FALSE(fs::exists(dir_ / "o"));
  WriteFile(dir_ / "jobs.yaml", "jobs:\n  - {name: small, maps: [" + A().string() + ", " +
                                    B().string() + "], output: o1, max_map_cells: 1000}\n" +
                                    "  - {name: fine, maps: [" + A().string() + ", " +
                                    B().string() + "], output: o2, max_map_cells: 2000000}\n");
  run = Fleetmerge("merge --quiet " + ShellQuote(dir_ / "jobs.yaml"));
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("job 'small' failed"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("more than the limit of 1000 cells"), std::string::npos) << run.err;
  EXPECT_TRUE(fs::exists(dir_ / "o2" / "merged_0.yaml")) << "the other job still ran";
}

TEST_F(MergeHardeningTest, AbsurdResolutionRefusedBeforeResampling) {
  // 1e-9 m per cell beside 0.05 m: robot_a would be resampled to 3e10 x 1.4e10 cells (the int
  // conversion overflowed before the check).
  std::string yaml = ReadFile(B());
  yaml.replace(yaml.find("resolution: "),
               yaml.find('\n', yaml.find("resolution: ")) - yaml.find("resolution: "),
               "resolution: 1e-9");
  WriteFile(dir_ / "ex" / "tiny_cells.yaml", yaml);
  const auto run = Fleetmerge("merge --quiet --out " + ShellQuote(dir_ / "o") + " " +
                              ShellQuote(A()) + " " + ShellQuote(dir_ / "ex" / "tiny_cells.yaml"));
  EXPECT_EQ(run.exit_code, 1);
  // Refused before any work (io/resampled_size.hpp), naming both files.
  EXPECT_NE(run.err.find(A().string() +
                         ": its 600 x 276 cells of 0.05 m would become 4.14e+20 "
                         "cells at 1e-09 m per cell (the finest resolution, that of " +
                         (dir_ / "ex" / "tiny_cells.yaml").string() + "), more than the limit"),
            std::string::npos)
      << run.err;
  EXPECT_FALSE(fs::exists(dir_ / "o"));
}

TEST_F(MergeHardeningTest, AnotherJobsResultsNeedForceAndForeignFilesAreKept) {
  const fs::path out = dir_ / "out";
  const std::string maps = ShellQuote(A()) + " " + ShellQuote(B());
  ASSERT_EQ(Fleetmerge("merge --quiet --out " + ShellQuote(out) + " " + maps).exit_code, 0);
  const std::string report = ReadFile(out / "report.json");
  auto run = Fleetmerge("merge --quiet --out " + ShellQuote(out) + " " + ShellQuote(A()));
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("holds the results of another job"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("--force"), std::string::npos) << run.err;
  EXPECT_EQ(ReadFile(out / "report.json"), report) << "old results untouched";
  run = Fleetmerge("merge --quiet --force --out " + ShellQuote(out) + " " + ShellQuote(A()));
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(json::parse(ReadFile(out / "report.json"))["maps"].size(), 1u);
  WriteFile(out / "my_notes.txt", "written by a person");
  run = Fleetmerge("merge --quiet --force --out " + ShellQuote(out) + " " + ShellQuote(A()));
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("did not write (e.g. 'my_notes.txt')"), std::string::npos) << run.err;
  EXPECT_EQ(ReadFile(out / "my_notes.txt"), "written by a person");
}

}  // namespace
}  // namespace fleetmerge
