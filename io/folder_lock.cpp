#include "io/folder_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <ctime>
#include <sstream>
#include <thread>

#include "core/error.hpp"

namespace fleetmerge {
namespace fs = std::filesystem;
namespace {

constexpr const char* kLockHeader = "fleetmerge folder lock v1";
constexpr const char* kLockTag = ".fleetmerge-lock";
// How often a waiting process retries: short next to a job (seconds), long next to a flock call.
constexpr auto kRetryPeriod = std::chrono::milliseconds(100);
// Longer waits (up to infinity) are cut to this, which the clock's nanoseconds still hold.
constexpr double kLongestWaitS = 1e9;

std::string NowUtc() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

std::string HostName() {
  char name[256] = {};
  if (gethostname(name, sizeof name - 1) != 0) return "unknown host";
  return name;
}

// Lines of the lock file hold one value each: no line breaks inside a value.
std::string OneLine(std::string text) {
  std::replace(text.begin(), text.end(), '\n', ' ');
  std::replace(text.begin(), text.end(), '\r', ' ');
  return text;
}

// The file's text as read through `fd` (at most a few kB: a lock file is a few lines).
std::string ReadLockText(int fd) {
  std::string text(4096, '\0');
  const ssize_t n = ::pread(fd, text.data(), text.size(), 0);
  text.resize(n > 0 ? static_cast<std::size_t>(n) : 0);
  return text;
}

// The holder through `fd`. A holder writes its lines just after it takes the lock, so a file
// read in between is empty (or half written): text that names no holder is read again for up to
// kHolderWriteGrace before it is reported as saying nothing (runs started at once into one
// folder otherwise now and then reported "does not say which" for a holder that was a run).
constexpr auto kHolderWriteGrace = std::chrono::milliseconds(100);
constexpr auto kHolderReread = std::chrono::milliseconds(2);
std::string DescribeHolder(int fd, const fs::path& lock_path) {
  const auto until = std::chrono::steady_clock::now() + kHolderWriteGrace;
  std::optional<FolderLockHolder> holder = ParseFolderLockFile(ReadLockText(fd));
  while (!holder && std::chrono::steady_clock::now() < until) {
    std::this_thread::sleep_for(kHolderReread);
    holder = ParseFolderLockFile(ReadLockText(fd));
  }
  if (!holder) {
    return "another process (its lock file " + lock_path.string() + " does not say which)";
  }
  return holder->job + " (pid " + std::to_string(holder->pid) + " on " + holder->host + ", since " +
         holder->since_utc + ")";
}

bool SameFile(int fd, const fs::path& path) {
  struct stat opened {
  }, named{};
  if (::fstat(fd, &opened) != 0 || ::stat(path.c_str(), &named) != 0) return false;
  return opened.st_dev == named.st_dev && opened.st_ino == named.st_ino;
}

std::string SecondsText(double seconds) {
  std::ostringstream out;
  out << seconds;
  return out.str();
}

}  // namespace

fs::path NormalisedFolder(const fs::path& folder) {
  fs::path path = fs::absolute(folder).lexically_normal();
  if (!path.has_filename()) path = path.parent_path();
  return path;
}

fs::path ResolvedFolder(const fs::path& folder) {
  fs::path path = NormalisedFolder(folder);
  std::error_code ec;
  // weakly_canonical alone leaves a link to a missing folder unresolved (the link's target is
  // what a job creates and locks): follow the last name's links by hand, up to the kernel's limit.
  for (int hops = 0; hops < 40; ++hops) {
    const fs::path parent = fs::weakly_canonical(path.parent_path(), ec);
    if (!ec) path = parent / path.filename();
    if (!fs::is_symlink(fs::symlink_status(path, ec))) break;
    const fs::path target = fs::read_symlink(path, ec);
    if (ec) break;
    path = NormalisedFolder(path.parent_path() / target);  // an absolute target replaces it all
  }
  return path;
}

fs::path FolderLockPath(const fs::path& folder, LockFilePlace place) {
  const fs::path path = ResolvedFolder(folder);
  if (place == LockFilePlace::kInsideFolder) return path / kLockTag;
  return path.parent_path() / ("." + path.filename().string() + kLockTag);
}

std::optional<FolderLockHolder> ParseFolderLockFile(const std::string& text) {
  std::istringstream in(text);
  std::string line;
  if (!std::getline(in, line) || line != kLockHeader) return std::nullopt;
  FolderLockHolder holder;
  bool have_pid = false, have_host = false, have_since = false, have_job = false;
  while (std::getline(in, line)) {
    if (line.rfind("pid: ", 0) == 0) {
      const std::string digits = line.substr(5);
      if (digits.empty() || digits.size() > 10 ||
          !std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; })) {
        return std::nullopt;
      }
      holder.pid = std::stol(digits);
      have_pid = holder.pid > 0;
    } else if (line.rfind("host: ", 0) == 0) {
      holder.host = line.substr(6);
      have_host = !holder.host.empty();
    } else if (line.rfind("since: ", 0) == 0) {
      holder.since_utc = line.substr(7);
      have_since = !holder.since_utc.empty();
    } else if (line.rfind("job: ", 0) == 0) {
      holder.job = line.substr(5);
      have_job = !holder.job.empty();
    } else if (!line.empty()) {
      return std::nullopt;
    }
  }
  if (!have_pid || !have_host || !have_since || !have_job) return std::nullopt;
  return holder;
}

FolderLock::FolderLock(const fs::path& folder, const std::string& job, double wait_s,
                       const std::string& label, const WaitNotice& notice, LockFilePlace place)
    : path_(FolderLockPath(folder, place)) {
  const std::string folder_name = NormalisedFolder(folder).string();  // as the caller spells it
  const double bounded_wait_s = wait_s > 0 ? std::min(wait_s, kLongestWaitS) : 0.0;  // NaN: 0
  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                            std::chrono::duration<double>(bounded_wait_s));
  bool announced = false;
  for (;;) {
    const int fd = ::open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
    if (fd < 0) {
      throw Error(path_.string() + ": cannot open the lock file of " + label + " " + folder_name +
                  ": " + std::strerror(errno));
    }
    if (::flock(fd, LOCK_EX | LOCK_NB) == 0) {
      if (SameFile(fd, path_)) {
        fd_ = fd;
        break;
      }
      ::close(fd);  // its holder removed it after we opened it: lock the path's new file
      continue;
    }
    const int error = errno;
    if (error != EWOULDBLOCK) {
      ::close(fd);
      throw Error(path_.string() + ": cannot lock " + label + " " + folder_name + ": " +
                  std::strerror(error));
    }
    const std::string holder = DescribeHolder(fd, path_);
    ::close(fd);
    const auto now = std::chrono::steady_clock::now();
    if (now >= deadline) {
      throw Error(label + " " + folder_name + " is in use by " + holder + "; " +
                  (wait_s > 0 ? "gave up after waiting " + SecondsText(wait_s) + " s"
                              : std::string("not waiting (lock wait 0)")) +
                  "; run the jobs one after the other, or give them different folders");
    }
    if (!announced && notice) notice(holder);
    announced = true;
    std::this_thread::sleep_for(
        std::min<std::chrono::steady_clock::duration>(kRetryPeriod, deadline - now));
  }
  std::ostringstream content;
  content << kLockHeader << "\npid: " << ::getpid() << "\nhost: " << OneLine(HostName())
          << "\nsince: " << NowUtc() << "\njob: " << OneLine(job) << "\n";
  const std::string text = content.str();
  // Only a message depends on it: a failed write leaves a file that names no holder.
  if (::ftruncate(fd_, 0) == 0) {
    [[maybe_unused]] const ssize_t written = ::pwrite(fd_, text.data(), text.size(), 0);
  }
}

FolderLock::~FolderLock() {
  if (fd_ < 0) return;
  // Removed while still locked; a waiter that opened this file sees it is gone and retries.
  if (SameFile(fd_, path_)) ::unlink(path_.c_str());
  ::close(fd_);
}

}  // namespace fleetmerge
