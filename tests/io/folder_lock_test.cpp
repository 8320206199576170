// FolderLock (io/folder_lock.hpp): one holder at a time, a busy lock named in the error, a
// holder killed with SIGKILL or a lock file left with garbage or a dead pid blocks nobody, and a
// ResultFolder holds its output folder's lock while it exists.
#include "io/folder_lock.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>
#include <string>
#include <thread>

#include "core/error.hpp"
#include "io/result_folder.hpp"
#include "tests/support/error_of.hpp"
#include "tests/support/files.hpp"
#include "tests/support/shared_data.hpp"

namespace fleetmerge {
namespace {

namespace fs = std::filesystem;
namespace ft = fleetmerge::testing;
using Clock = std::chrono::steady_clock;

using fleetmerge::testing::ErrorOf;

std::string HostName() {
  char name[256] = {};
  gethostname(name, sizeof name - 1);
  return name;
}

// A pid that no process has any more: a child that exited and was reaped.
pid_t DeadPid() {
  const pid_t pid = fork();
  if (pid == 0) _exit(0);
  waitpid(pid, nullptr, 0);
  return pid;
}

TEST(FolderLock, LockFileBesideTheFolderNamesTheHolder) {
  const fs::path dir = ft::MakeTempDir("folder_lock_holder");
  EXPECT_EQ(FolderLockPath(dir / "out/"), dir / ".out.fleetmerge-lock");
  EXPECT_EQ(FolderLockPath(dir / "." / "out"), dir / ".out.fleetmerge-lock");
  {
    FolderLock lock(dir / "out", "job 'daily' of /jobs/site.yaml", 0);
    EXPECT_EQ(lock.path(), dir / ".out.fleetmerge-lock");
    const std::optional<FolderLockHolder> holder =
        ParseFolderLockFile(ft::ReadFile(dir / ".out.fleetmerge-lock"));
    ASSERT_TRUE(holder.has_value());
    EXPECT_EQ(holder->pid, getpid());
    EXPECT_EQ(holder->host, HostName());
    EXPECT_EQ(holder->job, "job 'daily' of /jobs/site.yaml");
    EXPECT_EQ(holder->since_utc.size(), 20u) << holder->since_utc;  // 2026-12-02T12:30:00Z

    // A second holder (its own open file, as another process has) fails at once with wait 0.
    const auto start = Clock::now();
    const std::string error = ErrorOf([&] { FolderLock second(dir / "out", "job 'b'", 0); });
    EXPECT_LT(std::chrono::duration<double>(Clock::now() - start).count(), 1.0);
    EXPECT_NE(error.find("folder " + (dir / "out").string() +
                         " is in use by job 'daily' of "
                         "/jobs/site.yaml (pid " +
                         std::to_string(getpid()) + " on " + HostName() + ", since "),
              std::string::npos)
        << error;
    EXPECT_NE(error.find("not waiting"), std::string::npos) << error;
    EXPECT_NE(ErrorOf([&] { FolderLock other(dir / "out/", "job 'c'", 0); }), "")
        << "out/ is the same folder as out";
    EXPECT_EQ(ErrorOf([&] { FolderLock other(dir / "out2", "job 'd'", 0); }), "")
        << "another folder has its own lock";
  }
  EXPECT_FALSE(fs::exists(dir / ".out.fleetmerge-lock")) << "released: the file is removed";
  EXPECT_EQ(ErrorOf([&] { FolderLock again(dir / "out", "job 'b'", 0); }), "");
}

// A folder has one lock however it is spelled: through a link to it (or to a folder not made
// yet), or through a link among its parents.
TEST(FolderLock, ALinkToTheFolderSharesItsLock) {
  const fs::path dir = ft::MakeTempDir("folder_lock_link");
  fs::create_directories(dir / "real");
  fs::create_directory_symlink("real", dir / "link");
  fs::create_directory_symlink(dir / "later", dir / "to_missing");
  fs::create_directory_symlink(dir, dir / "parent_link");
  EXPECT_EQ(FolderLockPath(dir / "link"), dir / ".real.fleetmerge-lock");
  EXPECT_EQ(FolderLockPath(dir / "parent_link" / "link/"), dir / ".real.fleetmerge-lock");
  EXPECT_EQ(FolderLockPath(dir / "to_missing"), dir / ".later.fleetmerge-lock");
  FolderLock held(dir / "real", "job 'real'", 0);
  const std::string error = ErrorOf([&] { FolderLock other(dir / "link", "job 'link'", 0); });
  EXPECT_NE(error.find("is in use by job 'real'"), std::string::npos) << error;
}

TEST(FolderLock, WaiterGetsTheLockWhenTheHolderReleasesIt) {
  const fs::path dir = ft::MakeTempDir("folder_lock_wait");
  std::optional<FolderLock> first(std::in_place, dir / "out", "job 'first'", 0);
  const auto start = Clock::now();
  std::thread release([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    first.reset();
  });
  std::string noticed;
  {
    FolderLock second(dir / "out", "job 'second'", 30, "output folder",
                      [&](const std::string& holder) { noticed += holder + ";"; });
    const double waited_s = std::chrono::duration<double>(Clock::now() - start).count();
    EXPECT_GE(waited_s, 0.45);
    EXPECT_LT(waited_s, 10.0);
    EXPECT_EQ(ParseFolderLockFile(ft::ReadFile(second.path()))->job, "job 'second'");
  }
  release.join();
  EXPECT_EQ(noticed.rfind("job 'first' (pid ", 0), 0u) << noticed;
  EXPECT_EQ(noticed.find(';'), noticed.size() - 1) << "told once: " << noticed;
}

TEST(FolderLock, WaitRunsOutWithTheHolderNamed) {
  const fs::path dir = ft::MakeTempDir("folder_lock_timeout");
  FolderLock first(dir / "out", "job 'first'", 0);
  const auto start = Clock::now();
  const std::string error =
      ErrorOf([&] { FolderLock second(dir / "out", "job 'second'", 0.5, "output folder"); });
  const double waited_s = std::chrono::duration<double>(Clock::now() - start).count();
  EXPECT_GE(waited_s, 0.45);
  EXPECT_LT(waited_s, 5.0);
  EXPECT_EQ(error.rfind("output folder " + (dir / "out").string() + " is in use by job 'first'", 0),
            0u)
      << error;
  EXPECT_NE(error.find("gave up after waiting 0.5 s"), std::string::npos) << error;
}

// A holder killed with SIGKILL (no destructor runs, the file stays) blocks nobody: the kernel
// released its flock.
TEST(FolderLock, HolderKilledWithSigkillDoesNotBlock) {
  const fs::path dir = ft::MakeTempDir("folder_lock_kill");
  int ready[2];
  ASSERT_EQ(pipe(ready), 0);
  const pid_t child = fork();
  if (child == 0) {
    close(ready[0]);
    FolderLock lock(dir / "out", "job 'killed'", 0);
    (void)!write(ready[1], "x", 1);
    for (;;) pause();
  }
  close(ready[1]);
  char byte = 0;
  ASSERT_EQ(read(ready[0], &byte, 1), 1) << "the child took the lock";
  close(ready[0]);
  const std::string busy = ErrorOf([&] { FolderLock second(dir / "out", "job 'next'", 0); });
  EXPECT_NE(busy.find("in use by job 'killed' (pid " + std::to_string(child)), std::string::npos)
      << busy;
  kill(child, SIGKILL);
  waitpid(child, nullptr, 0);
  ASSERT_TRUE(fs::exists(dir / ".out.fleetmerge-lock")) << "a killed holder leaves its file";
  EXPECT_EQ(ParseFolderLockFile(ft::ReadFile(dir / ".out.fleetmerge-lock"))->pid, child);
  EXPECT_EQ(ErrorOf([&] { FolderLock next(dir / "out", "job 'next'", 0); }), "");
  EXPECT_FALSE(fs::exists(dir / ".out.fleetmerge-lock"));
}

// Lock files nobody holds, whatever they say, are not trusted: the next holder takes the lock at
// once and writes its own content.
TEST(FolderLock, LeftOverLockFilesDoNotBlock) {
  const fs::path dir = ft::MakeTempDir("folder_lock_leftover");
  const fs::path lock_file = dir / ".out.fleetmerge-lock";
  const std::vector<std::string> contents = {
      "",
      std::string("\0\xff garbage \n\n", 14),
      "fleetmerge folder lock v1\npid: 12x\nhost: h\nsince: s\njob: j\n",
      "fleetmerge folder lock v1\npid: " + std::to_string(DeadPid()) + "\nhost: " + HostName() +
          "\nsince: 2026-01-01T00:00:00Z\njob: job 'dead' of /jobs/site.yaml\n",
      std::string(100000, 'x'),
  };
  for (const std::string& content : contents) {
    SCOPED_TRACE(content.substr(0, 40));
    ft::WriteFile(lock_file, content);
    FolderLock lock(dir / "out", "job 'now'", 0);
    const std::optional<FolderLockHolder> holder = ParseFolderLockFile(ft::ReadFile(lock_file));
    ASSERT_TRUE(holder.has_value());
    EXPECT_EQ(holder->pid, getpid());
    EXPECT_EQ(holder->job, "job 'now'");
  }
  // Garbage names no holder; the dead process's file is well formed, and still blocked nothing.
  for (std::size_t k = 0; k < contents.size(); ++k) {
    EXPECT_EQ(ParseFolderLockFile(contents[k]).has_value(), k == 3) << contents[k].substr(0, 40);
  }
}

// A held lock whose file names no holder (garbage, or not yet written) is still a lock; the
// message says the file does not name the holder rather than trusting it.
TEST(FolderLock, HeldLockWithGarbageContentStillBlocks) {
  const fs::path dir = ft::MakeTempDir("folder_lock_garbage_held");
  FolderLock first(dir / "out", "job 'first'", 0);
  std::ofstream(first.path(), std::ios::trunc) << "not a lock file\n";  // same file, new bytes
  const std::string error = ErrorOf([&] { FolderLock second(dir / "out", "job 'second'", 0); });
  EXPECT_NE(error.find("is in use by another process (its lock file " + first.path().string() +
                       " does not say which)"),
            std::string::npos)
      << error;
}

// A holder writes its lines just after it takes the lock; a waiter that reads the file in
// between still names it (it reads again for a moment), rather than "does not say which".
TEST(FolderLock, HolderThatWritesItsLinesJustAfterLockingIsNamed) {
  const fs::path dir = ft::MakeTempDir("folder_lock_late_lines");
  const fs::path lock_file = FolderLockPath(dir / "out");
  const int fd = open(lock_file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(flock(fd, LOCK_EX | LOCK_NB), 0);  // locked, still empty
  std::thread holder([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    const std::string text = "fleetmerge folder lock v1\npid: " + std::to_string(getpid()) +
                             "\nhost: " + HostName() +
                             "\nsince: 2026-12-03T00:00:00Z\njob: job 'late'\n";
    (void)!pwrite(fd, text.data(), text.size(), 0);
  });
  const std::string error = ErrorOf([&] { FolderLock second(dir / "out", "job 'second'", 0); });
  holder.join();
  close(fd);
  EXPECT_NE(error.find("is in use by job 'late' (pid " + std::to_string(getpid())),
            std::string::npos)
      << error;
}

TEST(FolderLock, ResultFolderHoldsItsOutputFoldersLock) {
  const fs::path dir = ft::MakeTempDir("folder_lock_result");
  std::optional<ResultFolder> first(std::in_place, dir / "out", "job 'first'", false,
                                    std::vector<fs::path>{}, 0);
  ft::WriteFile(first->staging_dir() / "a.txt", "first");
  const std::string error = ErrorOf(
      [&] { ResultFolder second(dir / "out", "job 'second'", true, {}, /*lock_wait_s=*/0); });
  EXPECT_EQ(error.rfind("output folder " + (dir / "out").string() + " is in use by job 'first'", 0),
            0u)
      << error;
  EXPECT_TRUE(fs::exists(first->staging_dir() / "a.txt")) << "the busy job removed nothing";
  first->Publish({"a.txt"});
  first.reset();
  EXPECT_FALSE(fs::exists(dir / ".out.fleetmerge-lock"));
  ResultFolder second(dir / "out", "job 'second'", true, {}, 0);
  EXPECT_EQ(ft::ReadFile(dir / "out" / "a.txt"), "first");
}

}  // namespace
}  // namespace fleetmerge
