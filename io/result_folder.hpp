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
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace fleetmerge {

inline constexpr const char* kManifestName = ".fleetmerge-job";

struct ResultManifest {
  std::string job_id;
  std::vector<std::string> files;  // paths inside the folder ('/'-separated), the manifest excluded
};

// Reads `folder`/.fleetmerge-job. Throws fleetmerge::Error naming the file when it is missing or
// malformed.
ResultManifest ReadResultManifest(const std::filesystem::path& folder);

class ResultFolder {
 public:
  // Checks that `output_dir` may be replaced (see above; throws fleetmerge::Error saying why
  // not), removes what killed earlier runs left beside it, and creates an empty staging folder.
  ResultFolder(std::filesystem::path output_dir, std::string job_id, bool force,
               const std::vector<std::filesystem::path>& inputs);
  ResultFolder(const ResultFolder&) = delete;
  ResultFolder& operator=(const ResultFolder&) = delete;
  ~ResultFolder();  // removes the staging folder unless Publish succeeded

  // Where the job writes its files.
  const std::filesystem::path& staging_dir() const { return staging_dir_; }

  // Writes the manifest listing `files` (names in the staging folder, all of which must exist),
  // flushes the folder and swaps it in as the output folder; the old set is then deleted.
  void Publish(const std::vector<std::string>& files);

 private:
  std::filesystem::path output_dir_;
  std::filesystem::path staging_dir_;
  std::string job_id_;
  bool published_ = false;
};

}  // namespace fleetmerge
