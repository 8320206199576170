// All-or-nothing replacement of a job's output folder. A job's results are several files
// (merged maps, previews, report.json); per-file atomic renames would let a job killed half way
// leave last week's report.json beside this week's maps. So the new set is written into a
// staging folder beside the output folder and swapped in with one renameat2(RENAME_EXCHANGE):
// at every moment the output folder's name points at either the old complete set or the new
// complete set (or, before the first run, at nothing).
//
// File systems without RENAME_EXCHANGE (renameat2 fails with EINVAL/ENOSYS/ENOTSUP): the old
// folder is first renamed aside to `.<name>.fleetmerge-old.<random>`, then the staging folder
// renamed in. Between those two renames the output folder is absent while the old set is
// complete under the aside name; the next run puts it back (see Prepare) if no new set arrived.
//
// A folder fleetmerge wrote holds a manifest, `.fleetmerge-job`: the identity of the job that
// wrote it and the files it wrote. An existing output folder is replaced only when
//   - it holds no file the manifest does not list (files fleetmerge did not write are never lost;
//     an empty folder counts as ours; files in subfolders, such as merged_bag/metadata.yaml,
//     are listed by their relative paths),
//   - it holds none of the job's inputs (neither map files nor the job file), and
//   - its manifest names the same job, or `force` is set.
//
// An output folder named through a link (`--out link` where link points to a folder) is the
// link's target: the set replaces the target (staged beside it), and the link stays.
//
// One job at a time: a ResultFolder holds the output folder's lock (io/folder_lock.hpp) from
// before it looks at the folder until it is destroyed (after Publish, or when the job is
// abandoned). A second job writing the same folder waits for the first to finish (up to
// `lock_wait_s`) and then checks and replaces the first job's complete set as usual; so the
// staging and set-aside folders found beside the output folder are always a killed run's.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "io/folder_lock.hpp"

namespace fleetmerge {

inline constexpr const char* kManifestName = ".fleetmerge-job";
// How long a job waits by default for another job writing its output folder: longer than most
// jobs take, short enough that a hung job shows up in the daily run's log.
inline constexpr double kDefaultOutputLockWaitS = 300;

struct ResultManifest {
  std::string job_id;
  std::vector<std::string> files;  // paths inside the folder ('/'-separated), the manifest excluded
};

// Reads `folder`/.fleetmerge-job. Throws fleetmerge::Error naming the file when it is missing or
// malformed.
ResultManifest ReadResultManifest(const std::filesystem::path& folder);

class ResultFolder {
 public:
  // Locks `output_dir` (waiting up to `lock_wait_s` seconds, 0: not at all; `notice` is told
  // when it waits; the lock names `holder`, or `job_id` when it is empty), checks that it may be
  // replaced (see above; throws fleetmerge::Error saying why not, or naming the job holding the
  // lock), removes what killed earlier runs left beside it, and creates an empty staging folder.
  ResultFolder(std::filesystem::path output_dir, std::string job_id, bool force,
               const std::vector<std::filesystem::path>& inputs,
               double lock_wait_s = kDefaultOutputLockWaitS,
               const FolderLock::WaitNotice& notice = {}, const std::string& holder = {});
  ResultFolder(const ResultFolder&) = delete;
  ResultFolder& operator=(const ResultFolder&) = delete;
  ~ResultFolder();  // removes the staging folder unless Publish succeeded

  // Where the job writes its files.
  const std::filesystem::path& staging_dir() const { return staging_dir_; }

  // Writes the manifest listing `files` (names in the staging folder, all of which must exist),
  // fsyncs the staging folder and its subfolders and swaps it in as the output folder; the old
  // set is then deleted. The files themselves must have been fsynced by their writers
  // (WriteFileAtomically with kDurable or kFolderSyncedLater).
  void Publish(const std::vector<std::string>& files);

 private:
  std::filesystem::path output_dir_;
  std::optional<FolderLock> lock_;  // destroyed after the destructor's body removed staging_dir_
  std::filesystem::path staging_dir_;
  std::string job_id_;
  bool published_ = false;
};

}  // namespace fleetmerge
