#include "tests/support/unprivileged.hpp"

#include <grp.h>
#include <pwd.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <exception>
#include <stdexcept>

#include "core/error.hpp"

namespace fleetmerge::testing {
namespace {

// What the child reports through its pipe: a first byte saying how `work` ended, then the
// message.
constexpr char kReturned = 'R', kThrew = 'E', kOther = 'X', kUnreachable = 'U', kNoSwitch = 'S';

std::string ReadAll(int fd) {
  std::string text;
  char buffer[4096];
  for (;;) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n > 0) {
      text.append(buffer, static_cast<std::size_t>(n));
    } else if (n == 0 || errno != EINTR) {
      return text;
    }
  }
}

void WriteAll(int fd, const std::string& text) {
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n > 0) {
      done += static_cast<std::size_t>(n);
    } else if (n < 0 && errno != EINTR) {
      return;
    }
  }
}

}  // namespace

std::optional<UnprivilegedUser> UserWithoutPrivileges() {
  if (::geteuid() != 0) return UnprivilegedUser{::geteuid(), ::getegid(), false};
  const passwd* nobody = ::getpwnam("nobody");
  if (nobody == nullptr || nobody->pw_uid == 0) return std::nullopt;
  return UnprivilegedUser{nobody->pw_uid, nobody->pw_gid, true};
}

void GiveTo(const std::filesystem::path& path, const UnprivilegedUser& user) {
  if (!user.switched) return;
  const auto give = [&](const std::filesystem::path& p) {
    if (::lchown(p.c_str(), user.uid, user.gid) != 0) {
      throw std::runtime_error("cannot give " + p.string() + " to the unprivileged user");
    }
  };
  give(path);
  if (!std::filesystem::is_directory(path)) return;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(path)) give(entry.path());
}

std::optional<std::string> ErrorAs(const UnprivilegedUser& user,
                                   const std::filesystem::path& folder,
                                   const std::function<void()>& work) {
  const auto run = [&]() -> std::string {
    if (::access(folder.parent_path().c_str(), X_OK) != 0) return std::string(1, kUnreachable);
    try {
      work();
    } catch (const Error& e) {
      return kThrew + std::string(e.what());
    } catch (const std::exception& e) {
      return kOther + std::string(e.what());
    }
    return std::string(1, kReturned);
  };
  std::string outcome;
  if (!user.switched) {
    outcome = run();
  } else {
    int pipe_fds[2];
    if (::pipe(pipe_fds) != 0) throw std::runtime_error("ErrorAs: pipe failed");
    const pid_t child = ::fork();
    if (child < 0) throw std::runtime_error("ErrorAs: fork failed");
    if (child == 0) {
      ::close(pipe_fds[0]);
      // Groups first, then the group, then the user: after setuid nothing else may change.
      const bool switched = ::setgroups(0, nullptr) == 0 && ::setgid(user.gid) == 0 &&
                            ::setuid(user.uid) == 0 && ::geteuid() == user.uid;
      WriteAll(pipe_fds[1], switched ? run() : std::string(1, kNoSwitch));
      // _exit: no atexit handlers, static destructors or leak check of the test's process copy.
      ::_exit(0);
    }
    ::close(pipe_fds[1]);
    outcome = ReadAll(pipe_fds[0]);
    ::close(pipe_fds[0]);
    int status = 0;
    while (::waitpid(child, &status, 0) < 0 && errno == EINTR) {
    }
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || outcome.empty()) {
      throw std::runtime_error("ErrorAs: the unprivileged child failed (status " +
                               std::to_string(status) + ")");
    }
  }
  switch (outcome.front()) {
    case kReturned:
      return std::string();
    case kThrew:
      return outcome.substr(1);
    case kUnreachable:
      return std::nullopt;
    case kOther:
      throw std::runtime_error("ErrorAs: not a fleetmerge::Error: " + outcome.substr(1));
    default:
      throw std::runtime_error("ErrorAs: could not switch to user " + std::to_string(user.uid));
  }
}

}  // namespace fleetmerge::testing
