#include "pipeline/job_run.hpp"

#include <algorithm>
#include <chrono>
#include <optional>
#include <utility>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "fleetmerge/version.hpp"  // the cache's entries are valid for this version only
#include "io/atomic_file.hpp"
#include "io/map_inputs.hpp"
#include "io/octree_io.hpp"
#include "io/resampled_size.hpp"
#include "io/result_folder.hpp"
#include "pipeline/html_report.hpp"
#include "pipeline/launch_files.hpp"
#include "pipeline/preview.hpp"
#include "pipeline/report_json.hpp"
#include "rosbag/merged_bag.hpp"

namespace fleetmerge {
namespace {

using Clock = std::chrono::steady_clock;

// Each component's merged map file name, "" for an unmerged one: the names a written set has.
std::vector<std::string> MergedFileNames(const FleetResult& result) {
  std::vector<std::string> files(result.components.size());
  for (std::size_t c = 0; c < result.components.size(); ++c) {
    if (result.components[c].merged) files[c] = "merged_" + std::to_string(c) + ".yaml";
  }
  return files;
}

// How a job writes into its staging folder (io/result_folder.hpp). Each file is fsynced and its
// folder is not: ResultFolder::Publish fsyncs the folder and its subfolders once. And no file is
// checked against the job's inputs (`{}` as protected_inputs): ResultFolder made the folder new
// and empty after checking that the output folder holds no input, so none can be in it (the
// check costs two stats per input and file: ~6,000 for a 33-map job).
constexpr AtomicWrite kStaged = AtomicWrite::kFolderSyncedLater;

// Writes the merged maps and previews into `dir` (the staging folder); returns each component's
// merged map file name (MergedFileNames) and appends every file written to `written`.
std::vector<std::string> WriteOutputs(const std::filesystem::path& dir, const FleetResult& result,
                                      int threads, std::vector<std::string>& written) {
  const std::vector<std::string> files = MergedFileNames(result);
  for (std::size_t c = 0; c < result.components.size(); ++c) {
    const FleetComponent& component = result.components[c];
    if (!component.merged) continue;
    const std::string stem = "merged_" + std::to_string(c);
    SaveMap(*component.merged, dir / files[c], {}, kStaged);
    cv::Mat3b preview = component.preview;  // made while compositing, where it could be
    if (preview.empty()) {
      std::vector<CompositeInput> inputs;
      for (int m : component.maps) inputs.push_back({&result.maps[m], result.T_component_map[m]});
      preview = ColourPreview(inputs, *component.merged, threads);
    }
    SaveImage(preview, dir / (stem + "_preview.png"), {}, kStaged, threads);
    written.insert(written.end(), {files[c], stem + ".pgm", stem + "_preview.png"});
  }
  return files;
}

// merged_bag/ (rosbag/merged_bag.hpp): component 0's merged map on /map and component c's on
// /merged_<c>/map, each in its component's frame (the launch files' parent frame), and
// /tf_static with the launch files' transforms. A job with nothing merged gets a bag with
// /tf_static only (an empty TFMessage), so that every result set has the same files. Appends
// the files written to `written`.
void WriteMergedBag(const std::filesystem::path& dir, const Job& job, const FleetResult& result,
                    std::vector<std::string>& written) {
  std::vector<MergedBagMap> maps;
  for (std::size_t c = 0; c < result.components.size(); ++c) {
    if (!result.components[c].merged) continue;
    maps.push_back({c == 0 ? "/map" : "/merged_" + std::to_string(c) + "/map",
                    ParentFrame(job, static_cast<int>(c)), &*result.components[c].merged});
  }
  std::vector<std::string> unmerged;
  std::vector<StaticTransform> transforms;
  for (const MapTransform& t : MapTransforms(job, result, unmerged)) {
    transforms.push_back({t.parent_frame, t.child_frame, t.T_parent_child});
  }
  const std::int64_t stamp_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(
                                    std::chrono::system_clock::now().time_since_epoch())
                                    .count();
  const MergedBagFiles bag = MakeMergedBag(maps, transforms, stamp_ns);
  const std::filesystem::path folder = dir / kMergedBagFolder;
  std::error_code ec;
  std::filesystem::create_directory(folder, ec);
  if (ec) throw Error(folder.string() + ": cannot create the folder: " + ec.message());
  // The storage file first: no reader sees a metadata.yaml naming a missing file.
  WriteFileAtomically(folder / kMergedBagMcapName, bag.mcap, {}, kStaged);
  WriteFileAtomically(folder / kMergedBagMetadataName, bag.metadata_yaml, {}, kStaged);
  const std::string prefix = std::string(kMergedBagFolder) + "/";
  written.insert(written.end(), {prefix + kMergedBagMcapName, prefix + kMergedBagMetadataName});
}

// Each run replaces its output folder as a whole (io/result_folder.hpp): a cache inside it would
// be taken for a stranger's files (the next run refuses the folder) or replaced with the results.
void CheckCacheOutsideOutput(const Job& job) {
  std::error_code ec;
  const std::filesystem::path cache = std::filesystem::weakly_canonical(job.options.cache_dir, ec);
  std::filesystem::path output = std::filesystem::weakly_canonical(job.output_dir, ec);
  if (ec) return;  // reported by whichever fails to open
  // "out/" names the folder "out": no empty last component in the comparison.
  if (!output.empty() && output.filename().empty()) output = output.parent_path();
  const auto [o, c] = std::mismatch(output.begin(), output.end(), cache.begin(), cache.end());
  if (o == output.end()) {
    throw Error("cache folder " + job.options.cache_dir.string() + " is inside the output folder " +
                job.output_dir.string() +
                ", which every run replaces as a whole; put the cache beside it");
  }
}

}  // namespace

std::vector<LoadedMap> LoadJobMaps(const Job& job, int threads, std::vector<JobOctree>& octrees) {
  octrees.assign(job.maps.size(), {});
  std::vector<std::optional<LoadedMap>> loaded(job.maps.size());
  // A failure names the first failing map in job order (ParallelFor rethrows the lowest index).
  ParallelFor(job.maps.size(), threads, [&](std::size_t m) {
    const auto& path = job.maps[m].path;
    loaded[m] = IsOctreePath(path) ? LoadOctreeMap(path, job.options.octree, octrees[m])
                                   : LoadJobMap(job.maps[m], job.options.max_map_cells);
  });
  std::vector<LoadedMap> out;
  for (auto& map : loaded) out.push_back(std::move(*map));
  return out;
}

Job MapListJob(const std::vector<std::filesystem::path>& paths,
               const std::filesystem::path& output_dir, const std::optional<std::string>& reference,
               const FleetOptions& options, const std::vector<std::string>& topics) {
  Job job;
  job.name = "merge";
  job.output_dir = output_dir;
  job.options = options;
  std::vector<MapInput> inputs;
  for (const auto& path : paths) inputs.push_back({path, path, "", topics});
  job.maps = ExpandMapInputs(inputs);
  job.reference = reference.value_or(job.maps.empty() ? "" : job.maps.front().name);
  bool found = false;
  for (const auto& m : job.maps) found = found || m.name == job.reference;
  if (!found) throw Error("--reference '" + job.reference + "' is not one of the maps' names");
  return job;
}

namespace {

std::string CanonicalText(const std::filesystem::path& path) {
  std::error_code ec;
  const std::filesystem::path c = std::filesystem::weakly_canonical(path, ec);
  return (ec ? path : c).string();
}

// A map in an identity: its file, or (maps in memory, the library API) its name.
std::string MapIdentity(const JobMap& map) {
  return map.path.empty() ? "memory:" + map.name : CanonicalText(map.path);
}

}  // namespace

std::string JobIdentity(const Job& job) {
  if (!job.job_file.empty()) return "job '" + job.name + "' of " + CanonicalText(job.job_file);
  std::string maps = "maps";
  for (const JobMap& map : job.maps) maps += " " + MapIdentity(map);
  return maps;
}

std::string JobLockHolder(const Job& job) {
  if (!job.job_file.empty() || job.maps.empty()) return JobIdentity(job);
  std::string holder = "job '" + job.name + "' of " + MapIdentity(job.maps.front());
  const std::size_t more = job.maps.size() - 1;
  if (more > 0) {
    holder += " and " + std::to_string(more) + " more map" + (more == 1 ? "" : "s");
  }
  return holder;
}

JobOutcome RunLoadedJob(const Job& job, const std::vector<LoadedMap>& loaded,
                        const std::vector<JobOctree>& octrees, double load_ms,
                        const JobRunOptions& options) {
  const auto start = Clock::now();
  if (loaded.size() != job.maps.size()) {
    throw Error("internal: " + std::to_string(loaded.size()) + " maps loaded for a job of " +
                std::to_string(job.maps.size()));
  }
  const std::vector<JobOctree> no_octrees(job.maps.size());
  const std::vector<JobOctree>& job_octrees = octrees.empty() ? no_octrees : octrees;
  JobTiming timing;
  timing.load_ms = load_ms;
  std::vector<std::filesystem::path> protect;
  if (!job.job_file.empty()) protect.push_back(job.job_file);
  int reference = 0;
  for (std::size_t m = 0; m < job.maps.size(); ++m) {
    for (const auto& p : {loaded[m].metadata.yaml_path, loaded[m].metadata.image_path}) {
      if (!p.empty()) protect.push_back(p);
    }
    if (job.maps[m].name == job.reference) reference = static_cast<int>(m);
  }
  {  // a map that would not fit once resampled fails the job now, naming its file
    std::vector<const LoadedMap*> maps;
    for (const auto& l : loaded) maps.push_back(&l);
    CheckResampledSizes(maps, job.options.resolution_m, job.options.max_map_cells);
  }
  CheckTransformFrames(job);
  if (options.write && !job.options.cache_dir.empty()) CheckCacheOutsideOutput(job);
  // Checked before the work (a folder that may not be replaced fails the job now); every file
  // then goes to a staging folder, swapped in as a whole (io/result_folder.hpp).
  std::optional<ResultFolder> folder;
  if (options.write) {
    folder.emplace(job.output_dir, JobIdentity(job), options.force, protect, options.lock_wait_s,
                   options.lock_notice, JobLockHolder(job));
  }
  std::vector<const OccupancyGrid*> grids;
  for (const auto& l : loaded) grids.push_back(&l.grid);
  FixedPoses fixed;  // empty unless the job has a fixed (base) map
  for (std::size_t m = 0; m < job.maps.size(); ++m) {
    if (!job.maps[m].fixed) continue;
    fixed.resize(job.maps.size());
    fixed[m] = job.maps[m].T_merged_map;
  }
  PosePriors priors;  // empty unless a map has a known start pose
  for (std::size_t m = 0; m < job.maps.size(); ++m) {
    if (!job.maps[m].prior) continue;
    priors.resize(job.maps.size());
    priors[m] = job.maps[m].prior;
  }
  JobOutcome outcome;
  {
    std::optional<PairCache> cache;
    if (!job.options.cache_dir.empty()) {
      CacheFolderOptions cache_options;
      cache_options.max_bytes = job.options.cache_max_mb << 20;
      cache_options.lock_wait_s = options.lock_wait_s;
      cache_options.lock_notice = options.cache_lock_notice;
      cache_options.job = JobLockHolder(job);
      cache_options.inputs = protect;
      for (const JobMap& map : job.maps) cache_options.inputs.push_back(map.path);  // bags, octrees
      cache.emplace(job.options.cache_dir, FLEETMERGE_VERSION_STRING, cache_options);
    }
    FleetOptions fleet_options = job.options;
    fleet_options.previews = options.write;  // coloured while compositing: one sampling pass
    for (const JobMap& map : job.maps) fleet_options.map_names.push_back(map.name);
    outcome.result = MergeFleet(grids, reference, fixed, priors, fleet_options, options.progress,
                                cache ? &*cache : nullptr);
    if (cache) outcome.cache = cache->stats();  // MergeFleet closed it after the pairs
  }
  const FleetResult& result = outcome.result;

  std::vector<std::string> written;  // the result set's files, for its manifest
  std::vector<std::string> files;
  OctreeOutputs octree_outputs;
  std::vector<std::string> image_files;      // report.html's map images
  std::vector<std::string> transform_files;  // launch files and bag
  double images_ms = 0.0;
  if (folder) {
    const std::filesystem::path& dir = folder->staging_dir();
    std::vector<const OccupancyGrid*> maps;
    for (const OccupancyGrid& map : result.maps) maps.push_back(&map);
    // Two lanes: report.html's map images depend on the maps alone, so they are encoded while the
    // merged maps, octrees, launch files and bag are written (each lane mostly one core).
    ParallelFor(2, job.options.threads, [&](std::size_t lane) {
      if (lane == 0) {
        const auto images_start = Clock::now();
        image_files = WriteHtmlMapImages(maps, dir, {}, job.options.threads, kStaged);
        images_ms = MillisecondsSince(images_start);
        return;
      }
      const auto write_start = Clock::now();
      files = WriteOutputs(dir, result, job.options.threads, written);
      octree_outputs = WriteMergedOctrees(result, job_octrees, dir, {}, kStaged);
      for (const auto& f : octree_outputs.merged_files) {
        if (!f.empty()) written.push_back(f);
      }
      timing.write_ms = MillisecondsSince(write_start);
      timing.total_ms = load_ms + MillisecondsSince(start);
      WriteFileAtomically(dir / kRos2LaunchFile, Ros2TransformsLaunch(job, result), {}, kStaged);
      WriteFileAtomically(dir / kRos1LaunchFile, Ros1TransformsLaunch(job, result), {}, kStaged);
      transform_files = {kRos2LaunchFile, kRos1LaunchFile};
      WriteMergedBag(dir, job, result, transform_files);
    });
  } else {
    const auto write_start = Clock::now();
    files = MergedFileNames(result);
    octree_outputs.z_m = VerticalOffsets(result, job_octrees);
    octree_outputs.merged_files.assign(result.components.size(), "");
    timing.write_ms = MillisecondsSince(write_start);
    timing.total_ms = load_ms + MillisecondsSince(start);
  }
  outcome.report = MakeReport(job, result, files, timing);
  AddOctreesToReport(outcome.report, job_octrees, octree_outputs);
  if (outcome.cache) {
    const PairCacheStats& stats = *outcome.cache;
    outcome.report["cache"] = {{"dir", job.options.cache_dir.generic_string()},
                               {"max_mb", job.options.cache_max_mb},
                               {"pairs_cached", stats.pairs_cached},
                               {"pairs_computed", stats.pairs_computed},
                               {"maps_prepared", stats.maps_prepared},
                               {"preparations_kept", stats.preparations_kept},
                               {"entries_rejected", stats.rejected},
                               {"entries_evicted", stats.eviction.removed},
                               {"entries_in_use", stats.eviction.in_use},
                               {"bound_below_job", stats.eviction.over_bound},
                               {"write_failures", stats.write_failures}};
    if (!stats.first_write_error.empty()) {
      outcome.report["cache"]["first_write_error"] = stats.first_write_error;
    }
  }
  for (std::size_t c = 0; c < result.components.size(); ++c) {
    outcome.report["components"][c]["frame"] = ParentFrame(job, static_cast<int>(c));
  }
  for (std::size_t m = 0; m < loaded.size(); ++m) {
    outcome.report["maps"][m]["frame"] = ChildFrame(job, job.maps[m].name);
    if (!loaded[m].bag) continue;
    const BagMapInfo& bag = *loaded[m].bag;
    outcome.report["maps"][m]["bag"] = {{"path", bag.bag.generic_string()},
                                        {"topic", bag.topic},
                                        {"type", bag.type},
                                        {"frame_id", bag.frame_id},
                                        {"log_time_ns", bag.log_time_ns},
                                        {"stamp_ns", bag.stamp_ns}};
  }
  if (folder) {
    // report.html (pipeline/html_report.hpp) is part of the set; its write time (its images' and
    // its page's) is added to report.json after the page is made (the page shows the times
    // before it).
    const auto page_start = Clock::now();
    written.insert(written.end(), image_files.begin(), image_files.end());
    const std::vector<std::string> page_files =
        WriteHtmlPage(HtmlReportOfJob(job, loaded, result, outcome.report, files),
                      folder->staging_dir(), {}, kStaged);
    written.insert(written.end(), page_files.begin(), page_files.end());
    outcome.report["timing_ms"]["report_html"] = images_ms + MillisecondsSince(page_start);
    WriteFileAtomically(folder->staging_dir() / "report.json", outcome.report.dump(2) + "\n", {},
                        kStaged);
    written.push_back("report.json");
    written.insert(written.end(), transform_files.begin(), transform_files.end());
    folder->Publish(written);
  }
  return outcome;
}

JobOutcome RunJob(const Job& job, const JobRunOptions& options) {
  const auto start = Clock::now();
  std::vector<JobOctree> octrees;
  const std::vector<LoadedMap> loaded = LoadJobMaps(job, job.options.threads, octrees);
  return RunLoadedJob(job, loaded, octrees, MillisecondsSince(start), options);
}

}  // namespace fleetmerge
