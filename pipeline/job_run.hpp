// One fleet-merging job end to end: its maps loaded (io/; octrees with their floor plans), merged
// (pipeline/fleet_merge.hpp), and its result set written into its output folder: merged maps,
// previews, merged octrees and report.json, swapped in as a whole (io/result_folder.hpp).
// `fleetmerge merge` runs jobs from files; the library API runs jobs on maps already in memory.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "io/map_io.hpp"
#include "io/result_folder.hpp"
#include "job/job.hpp"
#include "pipeline/fleet_merge.hpp"
#include "pipeline/octree_maps.hpp"
#include "pipeline/pair_cache.hpp"

namespace fleetmerge {

struct JobRunOptions {
  bool write = true;   // false: compute only (nothing is written, output_dir is not touched)
  bool force = false;  // replace an output folder holding another job's results
  // Another job writing the same output folder: wait this long for it to finish (0: fail at
  // once); `lock_notice` is told when the job starts waiting (io/result_folder.hpp).
  double lock_wait_s = kDefaultOutputLockWaitS;
  FolderLock::WaitNotice lock_notice;
  // The same wait for another job using the job's cache folder (FleetOptions::cache_dir).
  FolderLock::WaitNotice cache_lock_notice;
  ProgressFn progress;
};

struct JobOutcome {
  FleetResult result;
  nlohmann::json report;                // report.json's contents (written or not)
  std::optional<PairCacheStats> cache;  // with a cache folder (FleetOptions::cache_dir)
};

// Loads the job's maps on `threads` threads (0: all cores); a failure is reported for the first
// failing map in job order, as a sequential load would. Octrees (.bt, .ot) come with their floor
// plans, and `octrees` gets one entry per map (empty for a 2-D map).
std::vector<LoadedMap> LoadJobMaps(const Job& job, int threads, std::vector<JobOctree>& octrees);

// The job of `fleetmerge merge --out DIR a.yaml b.bag ...`: named "merge", each map file one map
// and each bag one map per OccupancyGrid topic (`topics`: only these), named as
// io/map_inputs.hpp says (file stems, or the shortest unique trailing path where stems collide),
// the reference (a map name) by default the first map. Throws fleetmerge::Error for a file
// listed twice, a bag without the topics, or an unknown reference.
Job MapListJob(const std::vector<std::filesystem::path>& paths,
               const std::filesystem::path& output_dir, const std::optional<std::string>& reference,
               const FleetOptions& options, const std::vector<std::string>& topics = {});

// Who wrote an output folder (its manifest, io/result_folder.hpp): the job file and job name,
// or for a job without a file the set of maps. Rerunning the same job replaces its results;
// another job needs `force`.
std::string JobIdentity(const Job& job);

// The job as a lock's holder is named to a waiting job: a job file's job by its identity, a map
// list by its first map and how many more ("job 'merge' of /a/robot1.yaml and 11 more maps"),
// not every map as its identity does.
std::string JobLockHolder(const Job& job);

// Runs `job` on its maps already loaded: loaded[m] (and octrees[m], empty for a 2-D map, or an
// empty vector when the job has no octree) belongs to job.maps[m]. load_ms is reported as the
// load time. Throws fleetmerge::Error (or a filesystem error) when the output folder may not be
// replaced, is still in use by another job after options.lock_wait_s, or a file cannot be
// written; the folder is then unchanged.
JobOutcome RunLoadedJob(const Job& job, const std::vector<LoadedMap>& loaded,
                        const std::vector<JobOctree>& octrees, double load_ms,
                        const JobRunOptions& options = {});

// With job.options.cache_dir set, the pair cache (pipeline/pair_cache.hpp) is opened after the
// output folder and locked with the same wait, until the pairs are stored and the cache is
// trimmed to its size bound (then other jobs may use it while this one finishes); report.json gets
// a "cache" object with its counts. Throws fleetmerge::Error naming the cache folder when it is a
// file, cannot be created or is not writable.
//
// LoadJobMaps, then RunLoadedJob.
JobOutcome RunJob(const Job& job, const JobRunOptions& options = {});

}  // namespace fleetmerge
