// `fleetmerge merge`: runs fleet-merging jobs (pipeline/fleet_merge.hpp) from job files or from
// a list of maps, writes each job's merged maps, previews and report.json atomically, and keeps
// going when one job fails.
#pragma once

#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "io/result_folder.hpp"
#include "job/job.hpp"

namespace fleetmerge {

struct MergeCommand {
  std::vector<std::filesystem::path> inputs;     // job files, or maps with --out
  std::optional<std::filesystem::path> out_dir;  // set: `inputs` are maps forming one job
  std::optional<std::string> reference;          // with --out: a map name
  std::vector<std::string> topics;               // with --out: bags' map topics to read
  std::string tf_parent_frame = "map";           // with --out: transforms' frames
  std::string tf_child_frame = "{name}/map";
  bool quiet = false;
  bool force = false;  // replace an output folder holding another job's results
  double lock_wait_s = kDefaultOutputLockWaitS;  // for another job writing the same folder
  FleetOptions options;                          // with --out
  // With --out: "NAME" or "NAME=X,Y,YAW" (a fixed base map at that pose, default identity), and
  // "NAME=X,Y,YAW" or "NAME=X,Y,YAW,SIGMA_M,SIGMA_RAD" (a known start pose), as a job file's
  // fixed/pose and initial_pose/initial_pose_sigma (configs/README.md).
  std::vector<std::string> fixed_maps;
  std::vector<std::string> initial_poses;
  // Set for every job (job files' `cache` / `cache_max_mb` otherwise).
  std::optional<std::filesystem::path> cache_dir;
  std::optional<std::int64_t> cache_max_mb;
  // The options given on the command line, by long name ("--threads"). With job files, those
  // that a job file's keys also set (ApplyGivenOptions) apply to every job, over its keys, and
  // those of --out's map list (--reference, --topic, --tf-parent, --tf-child) are refused.
  std::vector<std::string> given;
};

// Copies into `job` (a job file's options) the options of `command` that its command line gave
// and that job files' keys also set: --threads, --omega-threshold, --octree-band-min/max,
// --max-map-cells and the method options (--n-theta, --rho-step, --hough-sampling,
// --spectra-sampling, --seed, --translation, --no-refine). A sampling option keeps the job's
// seed unless --seed is given too. Throws fleetmerge::Error when the height band they leave is
// empty, naming the options and the job.
void ApplyGivenOptions(const MergeCommand& command, const std::string& job_name, FleetOptions& job);

// The job described by `--out DIR a.yaml b.yaml ...`, with its --fixed and --initial-pose maps.
// Throws fleetmerge::Error naming the option and its value for a name that is no map's, a
// malformed or non-finite pose, a sigma <= 0, a map given twice, a fixed map with a start pose,
// or a --reference other than the first fixed map.
Job JobFromMapList(const MergeCommand& command);

// Runs the jobs in order; a failing job is reported on `err` and the others still run. Each
// job's output folder is replaced as a whole, only by a complete new result set
// (io/result_folder.hpp); `force` lets a job replace the results of another job. A job whose
// folder another process is writing waits up to `lock_wait_s` for it (0: fails at once).
// Returns 0 when every job ran (whatever got merged), 1 otherwise.
int RunJobs(const std::vector<Job>& jobs, bool quiet, std::ostream& out, std::ostream& err,
            bool force = false, double lock_wait_s = kDefaultOutputLockWaitS);

int RunMergeCommand(const MergeCommand& command, std::ostream& out, std::ostream& err);

}  // namespace fleetmerge
