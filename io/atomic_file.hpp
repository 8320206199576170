// Crash-safe file output: a reader of `path` sees either the old file or the complete new one,
// never a half-written file. The bytes go to a temporary file in the same folder (so the final
// rename stays on one file system and is atomic under POSIX), which is fsynced and then renamed
// over the target.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace fleetmerge {

// Throws fleetmerge::Error "refusing to overwrite input file X" when `path` names one of
// `protected_inputs`: the same file (std::filesystem::equivalent) when both exist, otherwise the
// same std::filesystem::weakly_canonical path.
void CheckNotAnInput(const std::filesystem::path& path,
                     const std::vector<std::filesystem::path>& protected_inputs);

// kDurable fsyncs the file and then its folder (the rename), so the new file survives a power cut.
// kFolderSyncedLater fsyncs the file only: for a folder that its owner fsyncs once, after all its
// files are written and before anyone reads it (a job's staging folder, io/result_folder.hpp),
// where a folder fsync per file would cost more than the files' own (a 33-map job writes 46).
// kNoSync skips both fsyncs: still all-or-nothing for readers while the machine runs, but after a
// power cut the file may be empty or old. Only for files whose readers check their bytes (cache
// entries carry a content hash, io/cache_folder.hpp) and would rather rebuild one than pay an
// fsync per file.
enum class AtomicWrite { kDurable, kFolderSyncedLater, kNoSync };

// Writes `bytes` to `path` atomically (temporary file `.name.tmp.<random>` beside it, fsync,
// rename; then the folder's fsync, as `mode` says). On any failure the temporary file is removed
// and fleetmerge::Error names the path and the reason. The folder must exist. If `path` is a
// symbolic link, the link itself is replaced.
void WriteFileAtomically(const std::filesystem::path& path, const std::string& bytes,
                         const std::vector<std::filesystem::path>& protected_inputs = {},
                         AtomicWrite mode = AtomicWrite::kDurable);

// fsyncs `folder` (its entries: the renames into it). Best effort: some file systems cannot fsync
// a folder, and a folder that cannot be opened is skipped.
void SyncFolder(const std::filesystem::path& folder);

}  // namespace fleetmerge
