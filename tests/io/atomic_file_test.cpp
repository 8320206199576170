#include "io/atomic_file.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <string>
#include <vector>

#include "core/error.hpp"
#include "tests/io/io_test_util.hpp"
#include "tests/support/shared_data.hpp"

namespace fleetmerge {
namespace {

namespace fs = std::filesystem;
namespace ft = fleetmerge::testing;

std::string ErrorOf(const fs::path& path, const std::string& bytes,
                    const std::vector<fs::path>& protected_inputs = {}) {
  try {
    WriteFileAtomically(path, bytes, protected_inputs);
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "WriteFileAtomically(" << path << ") did not throw";
  return "";
}

using ft::Contains;

TEST(AtomicFileTest, WritesExactBytesAndLeavesNoTemporaryFile) {
  const fs::path dir = ft::MakeTempDir("atomic_write");
  const std::string bytes("binary\0data\n\xff", 13);
  WriteFileAtomically(dir / "out.bin", bytes);
  EXPECT_EQ(ft::ReadFile(dir / "out.bin"), bytes);
  EXPECT_EQ(ft::FileNames(dir), (std::vector<std::string>{"out.bin"}));
}

TEST(AtomicFileTest, ReplacesAnExistingFile) {
  const fs::path dir = ft::MakeTempDir("atomic_replace");
  ft::WriteFile(dir / "out.txt", "old contents that are longer than the new ones\n");
  WriteFileAtomically(dir / "out.txt", "new\n");
  EXPECT_EQ(ft::ReadFile(dir / "out.txt"), "new\n");
  WriteFileAtomically(dir / "out.txt", "");
  EXPECT_EQ(ft::ReadFile(dir / "out.txt"), "");
  EXPECT_EQ(ft::FileNames(dir), (std::vector<std::string>{"out.txt"}));
}

// The modes differ only in what they fsync; a reader sees the old file or the whole new one in
// each, and no temporary file is left.
TEST(AtomicFileTest, EveryModeReplacesTheFileWhole) {
  for (const AtomicWrite mode :
       {AtomicWrite::kDurable, AtomicWrite::kFolderSyncedLater, AtomicWrite::kNoSync}) {
    const fs::path dir = ft::MakeTempDir("atomic_mode");
    ft::WriteFile(dir / "out.txt", "old contents that are longer than the new ones\n");
    WriteFileAtomically(dir / "out.txt", "new\n", {}, mode);
    EXPECT_EQ(ft::ReadFile(dir / "out.txt"), "new\n") << static_cast<int>(mode);
    EXPECT_EQ(ft::FileNames(dir), (std::vector<std::string>{"out.txt"})) << static_cast<int>(mode);
  }
}

TEST(AtomicFileTest, NewFileGetsUmaskPermissions) {
  const fs::path dir = ft::MakeTempDir("atomic_perms");
  const mode_t old_mask = ::umask(022);
  WriteFileAtomically(dir / "out.txt", "x");
  ::umask(old_mask);
  EXPECT_EQ(fs::status(dir / "out.txt").permissions(),
            fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read |
                fs::perms::others_read);
}

TEST(AtomicFileTest, MissingFolderThrowsWithPathAndReason) {
  const fs::path dir = ft::MakeTempDir("atomic_missing");
  const fs::path target = dir / "no_such_folder" / "out.txt";
  const std::string message = ErrorOf(target, "x");
  EXPECT_EQ(message.rfind(target.string() + ": ", 0), 0u) << message;
  EXPECT_TRUE(Contains(message, "No such file or directory")) << message;
  EXPECT_TRUE(ft::FileNames(dir).empty());
}

TEST(AtomicFileTest, FailedRenameRemovesTheTemporaryFile) {
  // The target is a non-empty folder: the temporary file is written, then the rename fails.
  const fs::path dir = ft::MakeTempDir("atomic_rename_fails");
  fs::create_directories(dir / "target" / "inside");
  const std::string message = ErrorOf(dir / "target", "x");
  EXPECT_EQ(message.rfind((dir / "target").string() + ": ", 0), 0u) << message;
  EXPECT_TRUE(Contains(message, "cannot rename temporary file")) << message;
  EXPECT_EQ(ft::FileNames(dir), (std::vector<std::string>{"target"}));
  EXPECT_EQ(ft::FileNames(dir / "target"), (std::vector<std::string>{"inside"}));
}

TEST(AtomicFileTest, PathThatIsNotAFileNameIsRejected) {
  const fs::path dir = ft::MakeTempDir("atomic_no_name");
  EXPECT_TRUE(Contains(ErrorOf(dir / "", "x"), "not a file name"));
  EXPECT_TRUE(ft::FileNames(dir).empty());
}

TEST(AtomicFileTest, ProtectedInputIsRefusedAndUnchanged) {
  const fs::path dir = ft::MakeTempDir("atomic_protect");
  ft::WriteFile(dir / "input.yaml", "original\n");
  const std::string message = ErrorOf(dir / "input.yaml", "clobbered", {dir / "input.yaml"});
  EXPECT_TRUE(
      Contains(message, "refusing to overwrite input file " + (dir / "input.yaml").string()))
      << message;
  EXPECT_EQ(ft::ReadFile(dir / "input.yaml"), "original\n");
  EXPECT_EQ(ft::FileNames(dir), (std::vector<std::string>{"input.yaml"}));
}

TEST(AtomicFileTest, ProtectedInputIsRecognisedUnderAnotherName) {
  const fs::path dir = ft::MakeTempDir("atomic_protect_alias");
  fs::create_directories(dir / "sub");
  ft::WriteFile(dir / "input.yaml", "original\n");
  fs::create_symlink(dir / "input.yaml", dir / "link.yaml");
  const std::vector<fs::path> inputs = {dir / "input.yaml"};
  EXPECT_TRUE(Contains(ErrorOf(dir / "sub" / ".." / "input.yaml", "x", inputs),
                       "refusing to overwrite input file"));
  EXPECT_TRUE(Contains(ErrorOf(dir / "link.yaml", "x", inputs), "(it is the input "));
  EXPECT_EQ(ft::ReadFile(dir / "input.yaml"), "original\n");
}

TEST(AtomicFileTest, CheckNotAnInputComparesPathsThatDoNotExistYet) {
  const fs::path dir = ft::MakeTempDir("atomic_check");
  const std::vector<fs::path> inputs = {dir / "a" / ".." / "map.yaml", dir / "other.pgm"};
  EXPECT_THROW(CheckNotAnInput(dir / "map.yaml", inputs), Error);
  EXPECT_NO_THROW(CheckNotAnInput(dir / "map.pgm", inputs));
  EXPECT_NO_THROW(CheckNotAnInput(dir / "map.yaml", {}));
}

}  // namespace
}  // namespace fleetmerge
