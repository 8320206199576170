#include "io/native_stderr.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cstdio>
#include <iostream>
#include <mutex>

namespace fleetmerge {
namespace {

std::mutex& StderrMutex() {
  static std::mutex mutex;
  return mutex;
}

std::string ReadAll(int fd) {
  std::string text;
  if (::lseek(fd, 0, SEEK_SET) != 0) return text;
  char buffer[4096];
  for (ssize_t n; (n = ::read(fd, buffer, sizeof buffer)) > 0;) text.append(buffer, n);
  return text;
}

// Restores descriptor 2 on every exit path.
class Redirect {
 public:
  explicit Redirect(int target) {
    std::fflush(stderr);
    std::cerr.flush();
    saved_ = ::dup(STDERR_FILENO);
    if (saved_ >= 0 && ::dup2(target, STDERR_FILENO) < 0) {
      ::close(saved_);
      saved_ = -1;
    }
  }
  Redirect(const Redirect&) = delete;
  Redirect& operator=(const Redirect&) = delete;
  ~Redirect() {
    if (saved_ < 0) return;
    std::fflush(stderr);
    std::cerr.flush();
    ::dup2(saved_, STDERR_FILENO);
    ::close(saved_);
  }
  bool active() const { return saved_ >= 0; }

 private:
  int saved_ = -1;
};

}  // namespace

std::string CaptureNativeStderr(const std::function<void()>& fn) {
  const std::lock_guard<std::mutex> lock(StderrMutex());
  std::FILE* file = std::tmpfile();
  if (file == nullptr) {
    fn();
    return "";
  }
  const int fd = ::fileno(file);
  std::string text;
  try {
    const Redirect redirect(fd);
    fn();
  } catch (...) {
    std::fclose(file);
    throw;
  }
  text = ReadAll(fd);
  std::fclose(file);
  return text;
}

}  // namespace fleetmerge
