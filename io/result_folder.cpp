#include "io/result_folder.hpp"

#include <fcntl.h>
#include <stdio.h>  // renameat2, RENAME_EXCHANGE (glibc >= 2.28)
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <random>
#include <set>
#include <sstream>

#include "core/error.hpp"
#include "io/atomic_file.hpp"

namespace fleetmerge {
namespace fs = std::filesystem;
namespace {

constexpr const char* kManifestHeader = "fleetmerge result set v1";
constexpr const char* kStagingTag = ".fleetmerge-staging.";
constexpr const char* kOldTag = ".fleetmerge-old.";

std::string RandomSuffix() {
  std::random_device device;
  std::ostringstream out;
  out << std::hex << device() << device();
  return out.str();
}

// `.<name><tag>` beside `output_dir`: the prefix of the staging and set-aside folders.
fs::path Sibling(const fs::path& output_dir, const std::string& tag) {
  return output_dir.parent_path() / ("." + output_dir.filename().string() + tag);
}

bool StartsWith(const std::string& text, const std::string& prefix) {
  return text.compare(0, prefix.size(), prefix) == 0;
}

bool IsInside(const fs::path& file, const fs::path& folder) {
  if (file.empty()) return false;
  std::error_code ec;
  const fs::path canonical_file = fs::weakly_canonical(file, ec);
  if (ec) return false;
  const fs::path canonical_folder = fs::weakly_canonical(folder, ec);
  if (ec) return false;
  const fs::path relative = canonical_file.lexically_relative(canonical_folder);
  return !relative.empty() && *relative.begin() != "..";
}

// What killed runs leave beside the output folder (called with the folder's lock held, so no
// running job owns any of it): staging folders (never published: removed)
// and, after a kill inside the two-rename fallback, the old set renamed aside (put back when the
// output folder is missing, else removed).
void RecoverLeftovers(const fs::path& output_dir) {
  const std::string staging_prefix = Sibling(output_dir, kStagingTag).filename().string();
  const std::string old_prefix = Sibling(output_dir, kOldTag).filename().string();
  std::error_code ec;
  std::vector<fs::path> staging, old;
  for (const auto& entry : fs::directory_iterator(output_dir.parent_path(), ec)) {
    const std::string name = entry.path().filename().string();
    if (StartsWith(name, staging_prefix)) staging.push_back(entry.path());
    if (StartsWith(name, old_prefix)) old.push_back(entry.path());
  }
  for (const fs::path& folder : staging) fs::remove_all(folder, ec);
  for (const fs::path& folder : old) {
    if (!fs::exists(output_dir, ec) && fs::exists(folder / kManifestName, ec)) {
      fs::rename(folder, output_dir, ec);
      if (!ec) continue;
    }
    fs::remove_all(folder, ec);
  }
}

// The files under `folder` by their paths relative to it ("merged_bag/metadata.yaml"), as the
// manifest names them; a folder holding nothing is listed as "<path>/" (a result set never has
// one, so it is not ours either).
std::set<std::string> PresentFiles(const fs::path& folder) {
  std::set<std::string> present;
  for (const auto& entry : fs::recursive_directory_iterator(folder)) {
    const std::string relative = entry.path().lexically_relative(folder).generic_string();
    std::error_code ec;
    if (!entry.is_directory(ec) || entry.is_symlink(ec)) {
      present.insert(relative);
    } else if (fs::is_empty(entry.path(), ec)) {
      present.insert(relative + "/");
    }
  }
  return present;
}

// Throws unless the existing `output_dir` may be replaced by a result set of `job_id`.
void CheckReplaceable(const fs::path& output_dir, const std::string& job_id, bool force,
                      const std::vector<fs::path>& inputs) {
  for (const fs::path& input : inputs) {
    if (IsInside(input, output_dir)) {
      throw Error("refusing to overwrite input file " + input.string() + ": it is inside the " +
                  "output folder " + output_dir.string() + ", which a run replaces as a whole; " +
                  "choose another output folder");
    }
  }
  std::set<std::string> present = PresentFiles(output_dir);
  if (present.empty()) return;
  const std::string refuse = "refusing to replace output folder " + output_dir.string() + ": ";
  if (present.count(kManifestName) == 0) {
    throw Error(refuse + "it holds files fleetmerge did not write (e.g. '" + *present.begin() +
                "'); move them away or choose another output folder");
  }
  const ResultManifest manifest = ReadResultManifest(output_dir);
  present.erase(kManifestName);
  for (const std::string& file : manifest.files) present.erase(file);
  if (!present.empty()) {
    throw Error(refuse + "it holds files fleetmerge did not write (e.g. '" + *present.begin() +
                "'); move them away or choose another output folder");
  }
  if (manifest.job_id != job_id && !force) {
    throw Error(refuse + "it holds the results of another job (" + manifest.job_id +
                "); use --force to replace them");
  }
}

// Swaps `staging` in as `output_dir`; returns the folder now holding the old set (empty path
// when there was none).
fs::path SwapIn(const fs::path& staging, const fs::path& output_dir) {
  if (::renameat2(AT_FDCWD, staging.c_str(), AT_FDCWD, output_dir.c_str(), RENAME_NOREPLACE) == 0) {
    return {};
  }
  if (errno == EEXIST || errno == ENOTEMPTY) {
    if (::renameat2(AT_FDCWD, staging.c_str(), AT_FDCWD, output_dir.c_str(), RENAME_EXCHANGE) ==
        0) {
      return staging;
    }
  }
  const int error = errno;
  if (error != EINVAL && error != ENOSYS && error != ENOTSUP && error != EEXIST &&
      error != ENOTEMPTY) {
    throw Error(output_dir.string() + ": cannot move the new results in from " + staging.string() +
                ": " + std::strerror(error));
  }
  // No renameat2 flags on this file system: two renames (the window documented in the header).
  std::error_code ec;
  fs::path aside;
  if (fs::exists(output_dir, ec)) {
    aside = Sibling(output_dir, kOldTag + RandomSuffix());
    fs::rename(output_dir, aside);
  }
  fs::rename(staging, output_dir);
  return aside;
}

}  // namespace

ResultManifest ReadResultManifest(const fs::path& folder) {
  const fs::path path = folder / kManifestName;
  std::ifstream in(path);
  std::string line;
  if (!in || !std::getline(in, line) || line != kManifestHeader) {
    throw Error(path.string() + ": missing or not a fleetmerge manifest (expected first line '" +
                kManifestHeader + "')");
  }
  ResultManifest manifest;
  bool have_job = false;
  while (std::getline(in, line)) {
    if (StartsWith(line, "job: ")) {
      manifest.job_id = line.substr(5);
      have_job = true;
    } else if (StartsWith(line, "file: ") && line.size() > 6) {
      manifest.files.push_back(line.substr(6));
    } else if (!line.empty()) {
      throw Error(path.string() + ": unexpected line '" + line.substr(0, 60) +
                  "', expected 'job: ...' or 'file: ...'");
    }
  }
  if (!have_job) throw Error(path.string() + ": no 'job: ...' line");
  return manifest;
}

ResultFolder::ResultFolder(fs::path output_dir, std::string job_id, bool force,
                           const std::vector<fs::path>& inputs, double lock_wait_s,
                           const FolderLock::WaitNotice& notice, const std::string& holder)
    // A link to a folder is kept: the set replaces the folder it points to.
    : output_dir_(ResolvedFolder(output_dir)), job_id_(std::move(job_id)) {
  std::replace(job_id_.begin(), job_id_.end(), '\n', ' ');  // the manifest is line-based
  std::error_code ec;
  fs::create_directories(output_dir_.parent_path(), ec);
  if (ec) {
    throw Error(output_dir_.string() + ": cannot create the folder that holds it (" +
                output_dir_.parent_path().string() + "): " + ec.message());
  }
  lock_.emplace(output_dir_, holder.empty() ? job_id_ : holder, lock_wait_s, "output folder",
                notice);
  RecoverLeftovers(output_dir_);  // the lock is ours: nobody else is writing beside the folder
  if (fs::exists(output_dir_, ec)) {
    if (!fs::is_directory(output_dir_, ec)) {
      throw Error(output_dir_.string() + ": exists and is not a folder");
    }
    CheckReplaceable(output_dir_, job_id_, force, inputs);
  }
  staging_dir_ = Sibling(output_dir_, kStagingTag + RandomSuffix());
  if (!fs::create_directory(staging_dir_, ec) || ec) {
    throw Error(output_dir_.string() + ": cannot create the staging folder " +
                staging_dir_.string() + ": " + (ec ? ec.message() : "it exists"));
  }
}

ResultFolder::~ResultFolder() {
  if (published_) return;
  std::error_code ignored;
  fs::remove_all(staging_dir_, ignored);
}

void ResultFolder::Publish(const std::vector<std::string>& files) {
  std::ostringstream manifest;
  manifest << kManifestHeader << "\njob: " << job_id_ << "\n";
  for (const std::string& file : files) {
    if (!fs::is_regular_file(staging_dir_ / file)) {
      throw Error(staging_dir_.string() + ": the result file '" + file + "' was not written");
    }
    manifest << "file: " << file << "\n";
  }
  // The files were fsynced as they were written, their folders were not (AtomicWrite::
  // kFolderSyncedLater): the subfolders now, the staging folder with the manifest.
  std::error_code ec;
  for (fs::recursive_directory_iterator it(staging_dir_, ec), end; !ec && it != end;
       it.increment(ec)) {
    if (it->is_directory(ec)) SyncFolder(it->path());
  }
  WriteFileAtomically(staging_dir_ / kManifestName, manifest.str());  // fsyncs it + the folder
  const fs::path old = SwapIn(staging_dir_, output_dir_);
  published_ = true;
  SyncFolder(output_dir_.parent_path());
  std::error_code ignored;
  if (!old.empty()) fs::remove_all(old, ignored);
}

}  // namespace fleetmerge
