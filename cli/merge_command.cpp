#include "cli/merge_command.hpp"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <exception>
#include <memory>
#include <optional>
#include <ostream>
#include <string>

#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "io/job_file.hpp"
#include "io/map_io.hpp"
#include "io/octree_io.hpp"
#include "io/result_folder.hpp"
#include "pipeline/fleet_merge.hpp"
#include "pipeline/octree_maps.hpp"
#include "pipeline/parallel.hpp"
#include "pipeline/preview.hpp"
#include "pipeline/report_json.hpp"

namespace fleetmerge {
namespace {

using Clock = std::chrono::steady_clock;

// "about 12 s left" for a stage `done` of `total` into it since `start`: its mean time per unit
// of work so far times the units left (pairs differ in cost, so this is a rough guide).
std::string TimeLeft(Clock::time_point start, int done, int total) {
  if (done <= 0 || done >= total) return "";
  const double seconds = MillisecondsSince(start) / 1000.0 * (total - done) / done;
  char text[48];
  std::snprintf(text, sizeof text, seconds < 10 ? "about %.1f s left" : "about %.0f s left",
                seconds);
  return text;
}

// A bar redrawn in place on a terminal; otherwise a line per stage about every quarter of its
// work and at its end. Before its end a stage also shows the time it has left.
ProgressFn MakeProgress(const std::string& job, bool quiet, std::ostream& err) {
  if (quiet) return {};
  const bool terminal = isatty(fileno(stderr)) != 0;
  // The stage being timed, when it started (the previous stage's last call, or now for the
  // first) and the last call (progress calls are serialised by the caller).
  struct Timing {
    std::string stage;
    Clock::time_point stage_start = Clock::now(), last_call = Clock::now();
  };
  auto timing = std::make_shared<Timing>();
  return [job, terminal, &err, timing](const std::string& stage, int done, int total) {
    if (timing->stage != stage) timing->stage = stage, timing->stage_start = timing->last_call;
    timing->last_call = Clock::now();
    const std::string left = TimeLeft(timing->stage_start, done, total);
    if (terminal) {
      const int width = 30, filled = total > 0 ? width * done / total : width;
      err << "\r" << job << " " << stage << " [" << std::string(filled, '#')
          << std::string(width - filled, ' ') << "] " << done << "/" << total
          << (left.empty() ? "" : ", " + left) << "    " << (done == total ? "\n" : "")
          << std::flush;
    } else if (done == total || (total >= 4 && done % ((total + 3) / 4) == 0)) {
      err << job << ": " << stage << " " << done << "/" << total
          << (left.empty() ? "" : " (" + left + ")") << "\n"
          << std::flush;
    }
  };
}

// Writes the merged maps and previews into `dir` (the staging folder); returns each component's
// merged map file name ("" for an unmerged one) and appends every file written to `written`.
std::vector<std::string> WriteOutputs(const std::filesystem::path& dir, const FleetResult& result,
                                      const std::vector<std::filesystem::path>& protect,
                                      std::vector<std::string>& written) {
  std::vector<std::string> files(result.components.size());
  for (std::size_t c = 0; c < result.components.size(); ++c) {
    const FleetComponent& component = result.components[c];
    if (!component.merged) continue;
    const std::string stem = "merged_" + std::to_string(c);
    files[c] = stem + ".yaml";
    SaveMap(*component.merged, dir / files[c], protect);
    std::vector<CompositeInput> inputs;
    for (int m : component.maps) inputs.push_back({&result.maps[m], result.T_component_map[m]});
    SaveImage(ColourPreview(inputs, *component.merged), dir / (stem + "_preview.png"), protect);
    written.insert(written.end(), {stem + ".yaml", stem + ".pgm", stem + "_preview.png"});
  }
  return files;
}

// Loads the job's maps on `threads` threads (0: all cores); a failure is reported for the first
// failing map in job order, as a sequential load would. Octrees (.bt, .ot) come with their floor
// plans, and `octrees` gets one entry per map (empty for a 2-D map).
std::vector<LoadedMap> LoadMaps(const Job& job, int threads, std::vector<JobOctree>& octrees) {
  octrees.assign(job.maps.size(), {});
  std::vector<std::optional<LoadedMap>> loaded(job.maps.size());
  std::vector<std::exception_ptr> failures(job.maps.size());
  ParallelFor(job.maps.size(), threads, [&](std::size_t m) {
    try {
      const auto& path = job.maps[m].path;
      loaded[m] = IsOctreePath(path) ? LoadOctreeMap(path, job.options.octree, octrees[m])
                                     : LoadMap(path, job.options.max_map_cells);
    } catch (...) {  // kept per map so that the first in job order is the one reported
      failures[m] = std::current_exception();
    }
  });
  std::vector<LoadedMap> out;
  for (std::size_t m = 0; m < job.maps.size(); ++m) {
    if (failures[m]) std::rethrow_exception(failures[m]);
    out.push_back(std::move(*loaded[m]));
  }
  return out;
}

// Who wrote an output folder (its manifest, io/result_folder.hpp): the job file and job name,
// or for `--out` the set of maps. Rerunning the same job replaces its results; another job
// needs --force.
std::string JobIdentity(const Job& job) {
  const auto canonical = [](const std::filesystem::path& path) {
    std::error_code ec;
    const std::filesystem::path c = std::filesystem::weakly_canonical(path, ec);
    return (ec ? path : c).string();
  };
  if (!job.job_file.empty()) return "job '" + job.name + "' of " + canonical(job.job_file);
  std::string maps = "maps";
  for (const JobMap& map : job.maps) maps += " " + canonical(map.path);
  return maps;
}

void RunJob(const Job& job, bool quiet, bool force, std::ostream& out, std::ostream& err) {
  const auto start = Clock::now();
  JobTiming timing;
  std::vector<JobOctree> octrees;
  const std::vector<LoadedMap> loaded = LoadMaps(job, job.options.threads, octrees);
  std::vector<std::filesystem::path> protect = {job.job_file};
  int reference = 0;
  for (std::size_t m = 0; m < job.maps.size(); ++m) {
    protect.push_back(loaded[m].metadata.yaml_path);
    protect.push_back(loaded[m].metadata.image_path);
    if (job.maps[m].name == job.reference) reference = static_cast<int>(m);
  }
  timing.load_ms = MillisecondsSince(start);
  // Checked before the work (a folder that may not be replaced fails the job now); every file
  // then goes to a staging folder, swapped in as a whole (io/result_folder.hpp).
  ResultFolder folder(job.output_dir, JobIdentity(job), force, protect);
  std::vector<const OccupancyGrid*> grids;
  for (const auto& l : loaded) grids.push_back(&l.grid);
  const FleetResult result =
      MergeFleet(grids, reference, job.options, MakeProgress(job.name, quiet, err));

  const auto write_start = Clock::now();
  std::vector<std::string> written;
  const std::vector<std::string> files =
      WriteOutputs(folder.staging_dir(), result, protect, written);
  const OctreeOutputs octree_outputs =
      WriteMergedOctrees(result, octrees, folder.staging_dir(), protect);
  for (const auto& f : octree_outputs.merged_files) {
    if (!f.empty()) written.push_back(f);
  }
  timing.write_ms = MillisecondsSince(write_start);
  timing.total_ms = MillisecondsSince(start);
  nlohmann::json report = MakeReport(job, result, files, timing);
  AddOctreesToReport(report, octrees, octree_outputs);
  WriteFileAtomically(folder.staging_dir() / "report.json", report.dump(2) + "\n", protect);
  written.push_back("report.json");
  folder.Publish(written);

  int merged = 0;
  for (const auto& c : result.components) merged += c.merged.has_value();
  out << job.name << ": " << job.maps.size() << " maps, " << result.components.size()
      << " component(s), " << merged
      << " merged map(s); report: " << (job.output_dir / "report.json").string() << " ("
      << static_cast<int>(timing.total_ms) << " ms)\n";
}

}  // namespace

Job JobFromMapList(const MergeCommand& command) {
  Job job;
  job.name = "merge";
  job.output_dir = *command.out_dir;
  job.options = command.options;
  for (const auto& path : command.inputs) {
    for (const JobMap& earlier : job.maps) {
      std::error_code ec;
      if (std::filesystem::equivalent(earlier.path, path, ec)) {
        throw Error(path.string() + " is listed twice (the same file as " + earlier.path.string() +
                    ")");
      }
      if (earlier.name == path.stem().string()) {
        throw Error(path.string() + " and " + earlier.path.string() + " would both be named '" +
                    earlier.name + "' (maps are named by file stem with --out; give them " +
                    "distinct file names or use a job file with 'name' keys)");
      }
    }
    job.maps.push_back({path.stem().string(), path, path});
  }
  job.reference = command.reference.value_or(job.maps.empty() ? "" : job.maps.front().name);
  bool found = false;
  for (const auto& m : job.maps) found = found || m.name == job.reference;
  if (!found) throw Error("--reference '" + job.reference + "' is not one of the maps' names");
  return job;
}

int RunJobs(const std::vector<Job>& jobs, bool quiet, std::ostream& out, std::ostream& err,
            bool force) {
  int failed = 0;
  for (const Job& job : jobs) {
    try {
      RunJob(job, quiet, force, out, err);
    } catch (const std::exception& e) {  // Error, filesystem_error, bad_alloc, cv::Exception
      ++failed;
      err << "fleetmerge: job '" << job.name << "' failed: " << e.what() << "\n";
    }
  }
  if (failed > 0) err << "fleetmerge: " << failed << " of " << jobs.size() << " job(s) failed\n";
  return failed > 0 ? 1 : 0;
}

int RunMergeCommand(const MergeCommand& command, std::ostream& out, std::ostream& err) {
  std::vector<Job> jobs;
  if (command.out_dir) {
    jobs.push_back(JobFromMapList(command));
  } else {
    // Every job file is validated before any job runs.
    for (const auto& file : command.inputs) {
      for (Job& job : LoadJobFile(file)) jobs.push_back(std::move(job));
    }
  }
  return RunJobs(jobs, command.quiet, out, err, command.force);
}

}  // namespace fleetmerge
