// File-permission checks that hold as root too. Root reads and writes any file, so a test of an
// unwritable folder or an unreadable file proves nothing when it runs as root, as it does on
// CI's fresh machines. There the check runs in a forked child switched to the `nobody` user;
// as any other user it runs in the test's own process.
#pragma once

#include <sys/types.h>

#include <filesystem>
#include <functional>
#include <optional>
#include <string>

namespace fleetmerge::testing {

struct UnprivilegedUser {
  uid_t uid = 0;
  gid_t gid = 0;
  bool switched = false;  // true: `nobody`, in a child process; false: the test's own user
};

// The test's own user when it is not root, else `nobody`; nullopt when the test runs as root and
// the system has no `nobody` (the caller skips, saying so).
std::optional<UnprivilegedUser> UserWithoutPrivileges();

// Makes `user` the owner of `path` and of everything under it (nothing to do for the test's own
// user), so it may write there as the owner would.
void GiveTo(const std::filesystem::path& path, const UnprivilegedUser& user);

// Runs `work` as `user` and returns the message of the fleetmerge::Error it threw, "" when it
// returned normally. nullopt when `user` cannot reach `folder` (it cannot search one of its
// parents: the caller skips, as the check would fail for that reason). As `nobody`, `work` runs
// in a child process: what it changes in memory does not reach the test.
std::optional<std::string> ErrorAs(const UnprivilegedUser& user,
                                   const std::filesystem::path& folder,
                                   const std::function<void()>& work);

}  // namespace fleetmerge::testing
