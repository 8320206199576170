// OctoMap octrees on disk: .bt (binary: occupancy only, free/occupied per leaf) and .ot (full
// log-odds) files of type OcTree, read and written with the OctoMap library.
//
// OctoMap reports a bad file on stderr and may return null, a half-read tree or throw, so the
// header is checked here first (magic line, "id", "size", "res", "data") and the error is ours:
// it names the file and what was expected. A tree of another type (ColorOcTree, OcTreeStamped,
// ...), an empty tree (size 0) and a truncated file (fewer nodes than "size") are refused.
#pragma once

#include <filesystem>
#include <memory>
#include <vector>

#include "io/atomic_file.hpp"

namespace octomap {
class OcTree;
}

namespace fleetmerge {

// True for a path ending in .bt or .ot (any case): the job's map entries so named are octrees.
bool IsOctreePath(const std::filesystem::path& path);

// Checks the file's header only (cheap; for validating a job file before any work).
void CheckOctreeFile(const std::filesystem::path& path);

// Reads a .bt or .ot file (chosen by the extension). Throws fleetmerge::Error naming the path.
std::unique_ptr<octomap::OcTree> LoadOctree(const std::filesystem::path& path);

// Writes the tree as .bt or .ot (chosen by the extension) through WriteFileAtomically (with
// `mode`); refuses to overwrite `protected_inputs` and an empty tree.
void SaveOctree(const octomap::OcTree& tree, const std::filesystem::path& path,
                const std::vector<std::filesystem::path>& protected_inputs = {},
                AtomicWrite mode = AtomicWrite::kDurable);

}  // namespace fleetmerge
