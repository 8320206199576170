// ResultFolder (io/result_folder.hpp): a result set replaces an output folder as a whole, only
// when that folder holds nothing fleetmerge did not write and none of the inputs, and only for
// the same job unless forced; leftovers of killed runs are cleaned up or put back.
#include "io/result_folder.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <string>

#include "core/error.hpp"
#include "tests/io/io_test_util.hpp"
#include "tests/support/error_of.hpp"
#include "tests/support/shared_data.hpp"

namespace fleetmerge {
namespace {

namespace fs = std::filesystem;
namespace ft = fleetmerge::testing;

// Publishes a set of one file `name` holding `text` into `out` for `job`.
void PublishSet(const fs::path& out, const std::string& job, const std::string& name,
                const std::string& text, bool force = false) {
  ResultFolder folder(out, job, force, {});
  ft::WriteFile(folder.staging_dir() / name, text);
  folder.Publish({name});
}

using fleetmerge::testing::ErrorOf;

std::vector<std::string> Entries(const fs::path& folder) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(folder)) names.push_back(e.path().filename());
  std::sort(names.begin(), names.end());
  return names;
}

TEST(ResultFolder, NewFolderThenReplacedBySameJob) {
  const fs::path dir = ft::MakeTempDir("result_folder_new");
  const fs::path out = dir / "sub" / "out";
  PublishSet(out, "job A", "report.json", "first");
  EXPECT_EQ(ft::ReadFile(out / "report.json"), "first");
  const ResultManifest manifest = ReadResultManifest(out);
  EXPECT_EQ(manifest.job_id, "job A");
  EXPECT_EQ(manifest.files, std::vector<std::string>{"report.json"});
  PublishSet(out, "job A", "merged_0.yaml", "second");  // the old set goes as a whole
  EXPECT_EQ(Entries(out), (std::vector<std::string>{".fleetmerge-job", "merged_0.yaml"}));
  EXPECT_EQ(Entries(dir / "sub"), std::vector<std::string>{"out"}) << "no staging left";
}

// `--out link` where link points to a folder: the set goes into the folder and the link stays
// (it was replaced by a folder of its own, leaving its target as it was); the lock is the target's.
TEST(ResultFolder, AnOutputFolderNamedThroughALinkIsTheLinksTarget) {
  const fs::path dir = ft::MakeTempDir("result_folder_link");
  fs::create_directories(dir / "target");
  fs::create_directory_symlink("target", dir / "link");
  fs::create_directory_symlink(dir / "later", dir / "to_missing");  // created by the first run
  for (const char* name : {"link", "to_missing"}) {
    PublishSet(dir / name, "job A", "report.json", "first");
    PublishSet(dir / name, "job A", "report.json", "second");
    EXPECT_TRUE(fs::is_symlink(dir / name)) << name;
    EXPECT_EQ(ft::ReadFile(dir / name / "report.json"), "second") << name;
  }
  EXPECT_EQ(ft::ReadFile(dir / "target" / "report.json"), "second");
  EXPECT_EQ(ft::ReadFile(dir / "later" / "report.json"), "second");
  ResultFolder held(dir / "target", "job A", false, {}, 0);
  const std::string error =
      ErrorOf([&] { ResultFolder other(dir / "link", "job A", false, {}, 0); });
  EXPECT_NE(error.find("is in use by job A"), std::string::npos) << error;
}

// A set with a subfolder (merged_bag/): the manifest lists its files by relative path, the set
// is replaced as a whole, and a file the user put inside the subfolder stops the replacement.
TEST(ResultFolder, SubfolderFilesAreListedAndGuarded) {
  const fs::path out = ft::MakeTempDir("result_folder_subfolder") / "out";
  const auto publish = [&](const std::string& text) {
    ResultFolder folder(out, "job A", false, {});
    fs::create_directory(folder.staging_dir() / "merged_bag");
    ft::WriteFile(folder.staging_dir() / "merged_bag" / "metadata.yaml", text);
    ft::WriteFile(folder.staging_dir() / "report.json", text);
    folder.Publish({"merged_bag/metadata.yaml", "report.json"});
  };
  publish("first");
  EXPECT_EQ(ReadResultManifest(out).files,
            (std::vector<std::string>{"merged_bag/metadata.yaml", "report.json"}));
  publish("second");
  EXPECT_EQ(ft::ReadFile(out / "merged_bag" / "metadata.yaml"), "second");
  ft::WriteFile(out / "merged_bag" / "notes.txt", "mine");
  const std::string message = ErrorOf([&] { publish("third"); });
  EXPECT_NE(message.find("did not write (e.g. 'merged_bag/notes.txt')"), std::string::npos)
      << message;
  EXPECT_EQ(ft::ReadFile(out / "merged_bag" / "notes.txt"), "mine");
  fs::remove(out / "merged_bag" / "notes.txt");
  fs::create_directory(out / "merged_bag" / "empty");
  EXPECT_NE(ErrorOf([&] { publish("fourth"); }).find("'merged_bag/empty/'"), std::string::npos);
  fs::remove(out / "merged_bag" / "empty");
  publish("fifth");
  EXPECT_EQ(ft::ReadFile(out / "report.json"), "fifth");
}

TEST(ResultFolder, AnotherJobNeedsForce) {
  const fs::path out = ft::MakeTempDir("result_folder_force") / "out";
  PublishSet(out, "job A", "report.json", "A");
  const std::string message = ErrorOf([&] { PublishSet(out, "job B", "report.json", "B"); });
  EXPECT_NE(message.find("holds the results of another job (job A); use --force"),
            std::string::npos)
      << message;
  EXPECT_EQ(ft::ReadFile(out / "report.json"), "A");
  PublishSet(out, "job B", "report.json", "B", /*force=*/true);
  EXPECT_EQ(ft::ReadFile(out / "report.json"), "B");
}

TEST(ResultFolder, ForeignFilesAreNeverReplacedEvenWithForce) {
  const fs::path dir = ft::MakeTempDir("result_folder_foreign");
  fs::create_directories(dir / "plain");
  ft::WriteFile(dir / "plain" / "notes.txt", "mine");
  std::string message = ErrorOf([&] { PublishSet(dir / "plain", "A", "r", "x", true); });
  EXPECT_NE(message.find("holds files fleetmerge did not write (e.g. 'notes.txt')"),
            std::string::npos)
      << message;
  PublishSet(dir / "ours", "A", "r", "x");
  ft::WriteFile(dir / "ours" / "extra.txt", "added by a user");
  message = ErrorOf([&] { PublishSet(dir / "ours", "A", "r", "y", true); });
  EXPECT_NE(message.find("'extra.txt'"), std::string::npos) << message;
  EXPECT_EQ(ft::ReadFile(dir / "ours" / "r"), "x");
  EXPECT_EQ(ft::ReadFile(dir / "plain" / "notes.txt"), "mine");
  fs::create_directories(dir / "empty");
  PublishSet(dir / "empty", "A", "r", "z");  // an empty folder is fine
  EXPECT_EQ(ft::ReadFile(dir / "empty" / "r"), "z");
}

TEST(ResultFolder, FolderHoldingAnInputIsRefused) {
  const fs::path dir = ft::MakeTempDir("result_folder_input");
  PublishSet(dir / "out", "A", "map.yaml", "an earlier result, now used as an input");
  const std::string message =
      ErrorOf([&] { ResultFolder folder(dir / "out", "A", true, {dir / "out" / "map.yaml"}); });
  EXPECT_NE(message.find("refusing to overwrite input file"), std::string::npos) << message;
  EXPECT_TRUE(fs::exists(dir / "out" / "map.yaml"));
}

TEST(ResultFolder, LeftoversOfKilledRunsAreCleanedOrPutBack) {
  const fs::path dir = ft::MakeTempDir("result_folder_leftovers");
  // A staging folder of a run killed while writing: removed by the next run.
  fs::create_directories(dir / ".out.fleetmerge-staging.dead");
  ft::WriteFile(dir / ".out.fleetmerge-staging.dead" / "report.json", "half");
  // The fallback's window: the old set renamed aside, the new one not yet in. Put back.
  PublishSet(dir / "out", "A", "report.json", "old complete set");
  fs::rename(dir / "out", dir / ".out.fleetmerge-old.dead");
  {
    ResultFolder folder(dir / "out", "A", false, {});
    EXPECT_EQ(ft::ReadFile(dir / "out" / "report.json"), "old complete set") << "put back";
    EXPECT_FALSE(fs::exists(dir / ".out.fleetmerge-staging.dead"));
    EXPECT_FALSE(fs::exists(dir / ".out.fleetmerge-old.dead"));
  }  // not published: its own staging folder goes too
  EXPECT_EQ(Entries(dir), std::vector<std::string>{"out"});
}

TEST(ResultFolder, PublishRefusesAMissingFile) {
  const fs::path out = ft::MakeTempDir("result_folder_missing") / "out";
  ResultFolder folder(out, "A", false, {});
  EXPECT_NE(ErrorOf([&] { folder.Publish({"never_written.pgm"}); }).find("was not written"),
            std::string::npos);
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace fleetmerge
