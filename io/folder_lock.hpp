// One writer at a time for a folder that whole jobs replace (an output folder) or share (a cache).
// Two fleetmerge runs writing one folder at once would each clean up what they take for a killed
// run's leftovers, i.e. each other's staging folders (io/result_folder.hpp), and fail.
//
// The lock is a file beside the folder, `.<name>.fleetmerge-lock` (or inside it, LockFilePlace),
// held with flock(2): the kernel releases it when the holder's process ends in any way (SIGKILL
// included), so a killed job never blocks the next one and no "stale lock" guessing is needed. The
// file's content (the holder's pid, host, start time and job) serves only to name the holder in
// messages; it is never trusted to decide whether the folder is locked, so a file left with a dead
// pid or garbage does not block.
//
// The holder removes the file on release. A process that locked a file the holder then removed
// sees that its file is no longer the one at the path (device and inode differ) and retries on
// the path's new file, so two processes never both hold the lock.
//
// flock(2) works between processes on one machine and, on Linux NFS clients, across machines
// (the client maps it to an NFS byte-range lock; not tested here).
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>

namespace fleetmerge {

// What a lock file says about its holder.
struct FolderLockHolder {
  long pid = 0;
  std::string host;
  std::string since_utc;  // "2026-12-02T12:30:00Z"
  std::string job;        // the job's identity (its file and name)
};

// `folder` absolute, without "." / ".." / a trailing '/', so that its parent is the folder that
// holds it ("out/" and "./out" are one folder).
std::filesystem::path NormalisedFolder(const std::filesystem::path& folder);

// The folder `folder` names, as NormalisedFolder, with every link followed (in its parents and in
// its own name, even when the link's target does not exist yet): one folder has one lock however
// it is spelled ("cache" and "link_to_cache" are one folder).
std::filesystem::path ResolvedFolder(const std::filesystem::path& folder);

// Where a folder's lock file lives. Beside it for a folder that jobs replace as a whole (an output
// folder: its parent must be writable anyway); inside it for a folder that is fleetmerge's and
// is never replaced (a cache: /var/cache/fleetmerge may be a service user's while /var/cache is
// root's).
enum class LockFilePlace { kBesideFolder, kInsideFolder };

// `.<name>.fleetmerge-lock` beside the folder `folder` resolves to (ResolvedFolder: "out/",
// "./out" and a link to out share it), or `.fleetmerge-lock` inside it.
std::filesystem::path FolderLockPath(const std::filesystem::path& folder,
                                     LockFilePlace place = LockFilePlace::kBesideFolder);

// The holder recorded in a lock file's text; nullopt unless it is well formed (the file may be
// half written, or garbage left by anything).
std::optional<FolderLockHolder> ParseFolderLockFile(const std::string& text);

class FolderLock {
 public:
  // Called once, with the holder's description ("job J (pid P on HOST, since T)"), when the lock
  // is busy and the caller is about to wait for it.
  using WaitNotice = std::function<void(const std::string& holder)>;

  // Locks `folder` (ResolvedFolder) for `job`, waiting up to `wait_s` seconds for another
  // holder to finish (0: not at all). The folder need not exist for a lock file beside it (the
  // folder holding it must), and must for one inside it. Throws fleetmerge::Error "<label> X is
  // in use by job J (pid P on HOST, since T); ..." when the wait runs out, or naming the lock
  // file when it cannot be opened or locked.
  FolderLock(const std::filesystem::path& folder, const std::string& job, double wait_s,
             const std::string& label = "folder", const WaitNotice& notice = {},
             LockFilePlace place = LockFilePlace::kBesideFolder);
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;
  ~FolderLock();  // removes the lock file and releases the lock

  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  int fd_ = -1;
};

}  // namespace fleetmerge
