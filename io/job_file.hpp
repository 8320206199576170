// Job files for `fleetmerge merge`: one job (a mapping with `maps`) or several (`jobs:` and a
// list of them), each naming its maps, its output folder and the method's parameters. The schema,
// with every key's type, range and default, is documented in configs/README.md.
#pragma once

#include <filesystem>
#include <vector>

#include "job/job.hpp"

namespace fleetmerge {

// Reads and validates every job of a job file before any work starts. Relative map and output
// paths are resolved against the job file's folder; each map YAML is read (not its image) so
// that a missing or malformed map stops the whole file. Throws fleetmerge::Error
//   "<yaml_path>: line L: key 'jobs[2].hough.n_theta': expected an integer in [8, 3600], got 'abc'"
// (lines 1-based, list indices 0-based) for unknown keys, missing keys, values of the wrong type
// or out of range, NaN or infinity, a job without maps, two maps of a job with one name or one
// file, a reference that names no map, and two jobs with one name or one output folder.
std::vector<Job> LoadJobFile(const std::filesystem::path& yaml_path);

}  // namespace fleetmerge
