#include "io/atomic_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <random>
#include <sstream>

#include "core/error.hpp"

namespace fleetmerge {
namespace fs = std::filesystem;
namespace {

[[noreturn]] void ThrowWriteError(const fs::path& path, const std::string& what, int error) {
  throw Error(path.string() + ": " + what + ": " + std::strerror(error));
}

// One stat per path: this runs for every file written against every input, and the files a
// job writes do not exist yet (canonicalising each pair of paths cost a merge of 33 maps about
// 48 000 system calls).
bool SameFile(const fs::path& a, const fs::path& b) {
  struct stat stat_a {};
  struct stat stat_b {};
  const bool a_exists = ::stat(a.c_str(), &stat_a) == 0;
  const bool b_exists = ::stat(b.c_str(), &stat_b) == 0;
  if (a_exists && b_exists) return stat_a.st_dev == stat_b.st_dev && stat_a.st_ino == stat_b.st_ino;
  if (a_exists || b_exists) return false;
  std::error_code ec;  // neither exists yet: the same path once '..' and links are resolved
  const fs::path canonical_a = fs::weakly_canonical(a, ec);
  if (ec) return a.lexically_normal() == b.lexically_normal();
  const fs::path canonical_b = fs::weakly_canonical(b, ec);
  if (ec) return a.lexically_normal() == b.lexically_normal();
  return canonical_a == canonical_b;
}

// Owns a POSIX file descriptor; Close() reports errors, the destructor ignores them (it only
// runs on the failure path, where an error is already being thrown).
class FileDescriptor {
 public:
  explicit FileDescriptor(int fd) : fd_(fd) {}
  FileDescriptor(const FileDescriptor&) = delete;
  FileDescriptor& operator=(const FileDescriptor&) = delete;
  ~FileDescriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  int get() const { return fd_; }
  int Close() {
    const int result = ::close(fd_);
    fd_ = -1;
    return result;
  }

 private:
  int fd_;
};

std::string RandomSuffix() {
  std::random_device device;
  std::ostringstream out;
  out << std::hex << device() << device();
  return out.str();
}

// Creates `.name.tmp.<random>` beside `path` with O_EXCL (never reusing an existing file) and
// mode 0666 & ~umask, so the final file gets the permissions an ordinary write would give it.
int CreateTempFile(const fs::path& path, fs::path* temp_path) {
  const fs::path folder = path.has_parent_path() ? path.parent_path() : fs::path(".");
  for (int attempt = 0;; ++attempt) {
    *temp_path = folder / ("." + path.filename().string() + ".tmp." + RandomSuffix());
    const int fd = ::open(temp_path->c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0) return fd;
    if (errno != EEXIST || attempt >= 10) {
      ThrowWriteError(path, "cannot create temporary file '" + temp_path->string() + "'", errno);
    }
  }
}

void WriteAll(int fd, const std::string& bytes, const fs::path& path) {
  const char* data = bytes.data();
  std::size_t remaining = bytes.size();
  while (remaining > 0) {
    const ssize_t written = ::write(fd, data, remaining);
    if (written < 0) {
      if (errno == EINTR) continue;
      ThrowWriteError(path, "cannot write temporary file", errno);
    }
    data += written;
    remaining -= static_cast<std::size_t>(written);
  }
}

void WriteAndRename(int raw_fd, const fs::path& temp_path, const fs::path& path,
                    const std::string& bytes, AtomicWrite mode) {
  FileDescriptor fd(raw_fd);
  WriteAll(fd.get(), bytes, path);
  if (mode != AtomicWrite::kNoSync && ::fsync(fd.get()) != 0)
    ThrowWriteError(path, "cannot flush temporary file", errno);
  if (fd.Close() != 0) ThrowWriteError(path, "cannot close temporary file", errno);
  std::error_code ec;
  fs::rename(temp_path, path, ec);
  if (ec) {
    throw Error(path.string() + ": cannot rename temporary file '" + temp_path.string() +
                "' over it: " + ec.message());
  }
}

}  // namespace

void CheckNotAnInput(const fs::path& path, const std::vector<fs::path>& protected_inputs) {
  for (const fs::path& input : protected_inputs) {
    if (!SameFile(path, input)) continue;
    std::string message = "refusing to overwrite input file " + path.string();
    if (path != input) message += " (it is the input " + input.string() + ")";
    throw Error(message);
  }
}

void SyncFolder(const fs::path& folder) {
  const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

void WriteFileAtomically(const fs::path& path, const std::string& bytes,
                         const std::vector<fs::path>& protected_inputs, AtomicWrite mode) {
  CheckNotAnInput(path, protected_inputs);
  if (!path.has_filename()) throw Error(path.string() + ": not a file name (ends in a '/')");
  fs::path temp_path;
  const int fd = CreateTempFile(path, &temp_path);
  try {
    WriteAndRename(fd, temp_path, path, bytes, mode);
  } catch (...) {
    std::error_code ignored;
    fs::remove(temp_path, ignored);
    throw;
  }
  // Makes the rename itself durable.
  if (mode == AtomicWrite::kDurable) {
    SyncFolder(path.has_parent_path() ? path.parent_path() : fs::path("."));
  }
}

}  // namespace fleetmerge
