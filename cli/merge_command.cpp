#include "cli/merge_command.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <memory>
#include <ostream>
#include <sstream>
#include <string>
#include <utility>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "io/job_file.hpp"
#include "pipeline/job_run.hpp"

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

// "0.3" for 300 kB: one decimal.
std::string MebibytesText(std::int64_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f", static_cast<double>(bytes) / (1 << 20));
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

// One line per group of maps that priors placed (PlacedBy::kPrior): a map alone, or maps that
// accepted pairs link to each other only, with the maps whose initial_pose placed them.
void PrintPlacedByPriors(const Job& job, const FleetResult& result, std::ostream& out) {
  const int map_count = static_cast<int>(job.maps.size());
  const std::vector<int> group_of = Components(map_count, result.pairs);
  std::vector<bool> printed(map_count, false);
  for (int m = 0; m < map_count; ++m) {
    if (result.placed_by[m] != PlacedBy::kPrior || printed[group_of[m]]) continue;
    printed[group_of[m]] = true;
    std::vector<std::string> members, with_prior;
    for (int k = 0; k < map_count; ++k) {
      if (group_of[k] != group_of[m]) continue;
      members.push_back(job.maps[k].name);
      if (job.maps[k].prior) with_prior.push_back(job.maps[k].name);
    }
    const auto list = [](const std::vector<std::string>& names) {
      std::string text;
      for (std::size_t k = 0; k < names.size(); ++k) {
        text += (k == 0 ? "" : k + 1 == names.size() ? " and " : ", ") + names[k];
      }
      return text;
    };
    out << job.name << ": " << list(members);
    if (members.size() == 1) {
      out << " placed by its initial_pose (no accepted pair links it to another map)\n";
    } else {
      out << " placed by the initial_pose" << (with_prior.size() == 1 ? " of " : "s of ")
          << list(with_prior) << " (accepted pairs link them to each other only)\n";
    }
  }
}

// Runs one job (pipeline/job_run.hpp) and prints its one-line summary.
void RunAndPrintJob(const Job& job, bool quiet, bool force, double lock_wait_s, std::ostream& out,
                    std::ostream& err) {
  JobRunOptions options;
  options.force = force;
  options.lock_wait_s = lock_wait_s;
  // Shown even with --quiet: a quiet cron job must not stall for minutes without a word.
  options.lock_notice = [&job, lock_wait_s, &err](const std::string& holder) {
    err << job.name << ": waiting up to " << lock_wait_s << " s for output folder "
        << job.output_dir.string() << ", in use by " << holder << "\n"
        << std::flush;
  };
  options.cache_lock_notice = [&job, lock_wait_s, &err](const std::string& holder) {
    err << job.name << ": waiting up to " << lock_wait_s << " s for cache folder "
        << job.options.cache_dir.string() << ", in use by " << holder << "\n"
        << std::flush;
  };
  options.progress = MakeProgress(job.name, quiet, err);
  const JobOutcome outcome = RunJob(job, options);
  const FleetResult& result = outcome.result;
  int merged = 0;
  for (const auto& c : result.components) merged += c.merged.has_value();
  out << job.name << ": " << job.maps.size() << " maps, " << result.components.size()
      << " component(s), " << merged
      << " merged map(s); report: " << (job.output_dir / "report.json").string() << " ("
      << static_cast<int>(outcome.report["timing_ms"]["total"].get<double>()) << " ms)\n";
  // Known start poses decide things the user must see: pairs they refused, maps they placed.
  for (const PairOutcome& p : result.pairs) {
    if (!p.refused_by_priors) continue;
    out << job.name << ": pair " << job.maps[p.a].name << " + " << job.maps[p.b].name << " "
        << p.note << "\n";
  }
  PrintPlacedByPriors(job, result, out);
  if (outcome.cache) {
    const PairCacheStats& cache = *outcome.cache;
    out << job.name << ": pairs: " << cache.pairs_cached << " from the cache, "
        << cache.pairs_computed << " computed";
    if (cache.maps_prepared > 0) {  // the maps of the pairs computed
      out << "; maps' preparations: " << cache.preparations_kept << " from the cache, "
          << cache.maps_prepared - cache.preparations_kept << " made";
    }
    if (cache.rejected > 0) out << "; " << cache.rejected << " bad cache entries rebuilt";
    // Never this job's entries (CacheFolder::Evict): older ones, of this job or others.
    if (cache.eviction.removed > 0) {
      out << "; " << cache.eviction.removed << " older cache entries evicted";
    }
    out << "\n";
    if (cache.eviction.over_bound) {
      err << "fleetmerge: warning: job '" << job.name << "': the cache's size bound ("
          << job.options.cache_max_mb << " MiB, --cache-max-mb / cache_max_mb) is below this job's "
          << cache.eviction.in_use << " entries, its pairs and maps' preparations ("
          << MebibytesText(cache.eviction.in_use_bytes) << " MiB); they were all kept, so "
          << job.options.cache_dir.string()
          << " holds more than its bound; raise the bound to keep other jobs' entries too\n";
    }
    if (cache.write_failures > 0) {
      err << "fleetmerge: warning: job '" << job.name << "': " << cache.write_failures
          << " cache entries (pairs or maps' preparations) could not be stored: "
          << cache.first_write_error << "\n";
    }
  }
}

// A --fixed or --initial-pose value: NAME=X,Y,YAW, NAME=X,Y,YAW,SIGMA_M,SIGMA_RAD (a start pose
// only) or NAME alone (a fixed map only: at the identity).
struct MapPoseOption {
  std::size_t map = 0;          // index in the job's maps
  std::vector<double> numbers;  // empty for a bare NAME
};

MapPoseOption ParseMapPoseOption(const std::string& flag, const std::string& value, bool fixed,
                                 const Job& job) {
  const std::string expected =
      fixed ? "NAME or NAME=X,Y,YAW (metres, radians)"
            : "NAME=X,Y,YAW or NAME=X,Y,YAW,SIGMA_M,SIGMA_RAD (metres, radians)";
  const auto fail = [&](const std::string& why) {
    return Error(flag + " '" + value + "': " + why + "; expected " + expected);
  };
  // Numbers hold no '=', so the last one ends the name.
  const std::size_t equals = value.rfind('=');
  const std::string name = value.substr(0, equals);
  MapPoseOption option;
  const auto named = std::find_if(job.maps.begin(), job.maps.end(),
                                  [&](const JobMap& map) { return map.name == name; });
  if (named == job.maps.end()) {
    throw Error(flag + " '" + value + "': no map is named '" + name +
                "' (the maps: " + QuotedMapNames(job.maps) + ")");
  }
  option.map = static_cast<std::size_t>(named - job.maps.begin());
  if (equals == std::string::npos) {
    if (!fixed) throw fail("no pose given");
    return option;
  }
  const std::string text = value.substr(equals + 1);
  if (text.empty() || text.back() == ',') throw fail("a number is missing");
  std::istringstream numbers(text);
  for (std::string word; std::getline(numbers, word, ',');) {
    // Spaces around a number are fine ("1, 2, 3", as a shell user quotes it); hexadecimal, which
    // strtod would take, is not a pose.
    const std::size_t first = word.find_first_not_of(' ');
    word = first == std::string::npos ? ""
                                      : word.substr(first, word.find_last_not_of(' ') - first + 1);
    char* end = nullptr;
    const double number = std::strtod(word.c_str(), &end);
    if (word.empty() || end != word.c_str() + word.size() || !std::isfinite(number) ||
        word.find_first_of("xX") != std::string::npos) {
      throw fail("'" + word + "' is not a finite number");
    }
    option.numbers.push_back(number);
  }
  if (option.numbers.size() != 3 && (fixed || option.numbers.size() != 5)) {
    throw fail(std::to_string(option.numbers.size()) + " numbers");
  }
  if (std::abs(option.numbers[2]) > kMaxYawRad) {
    throw fail("YAW " + YawLooksLikeDegrees(option.numbers[2]) + "; at most 2 pi in magnitude");
  }
  if (option.numbers.size() == 5 && option.numbers[4] > kMaxYawSigmaRad) {
    throw fail("SIGMA_RAD " + YawLooksLikeDegrees(option.numbers[4]) + "; at most pi");
  }
  return option;
}

// A sampling option given on the command line: the job's seed stays unless --seed is given.
void CopyKeepingSeed(const SamplingOptions& given, SamplingOptions& job) {
  const std::uint32_t seed = job.seed;
  job = given;
  job.seed = seed;
}

// merge's options that job files' keys also set (configs/README.md), and how each is copied from
// the command line's options into a job's.
struct JobKeyOption {
  const char* name;
  void (*copy)(const FleetOptions& given, FleetOptions& job);
};
// In this order: a sampling option keeps the job's seed, which --seed (after it) then sets.
const JobKeyOption kJobKeyOptions[] = {
    {"--threads", [](const FleetOptions& g, FleetOptions& j) { j.threads = g.threads; }},
    {"--omega-threshold",
     [](const FleetOptions& g, FleetOptions& j) { j.omega_threshold = g.omega_threshold; }},
    {"--octree-band-min",
     [](const FleetOptions& g, FleetOptions& j) { j.octree.band_min_m = g.octree.band_min_m; }},
    {"--octree-band-max",
     [](const FleetOptions& g, FleetOptions& j) { j.octree.band_max_m = g.octree.band_max_m; }},
    {"--max-map-cells",
     [](const FleetOptions& g, FleetOptions& j) { j.max_map_cells = g.max_map_cells; }},
    {"--n-theta",
     [](const FleetOptions& g, FleetOptions& j) {
       j.pair.hypotheses.hough.n_theta = g.pair.hypotheses.hough.n_theta;
     }},
    {"--rho-step",
     [](const FleetOptions& g, FleetOptions& j) {
       j.pair.hypotheses.hough.rho_step_cells = g.pair.hypotheses.hough.rho_step_cells;
     }},
    {"--hough-sampling",
     [](const FleetOptions& g, FleetOptions& j) {
       CopyKeepingSeed(g.pair.hypotheses.hough_sampling, j.pair.hypotheses.hough_sampling);
     }},
    {"--spectra-sampling",
     [](const FleetOptions& g, FleetOptions& j) {
       CopyKeepingSeed(g.pair.hypotheses.spectra_sampling, j.pair.hypotheses.spectra_sampling);
     }},
    {"--seed",
     [](const FleetOptions& g, FleetOptions& j) {
       j.pair.hypotheses.hough_sampling.seed = g.pair.hypotheses.hough_sampling.seed;
       j.pair.hypotheses.spectra_sampling.seed = g.pair.hypotheses.spectra_sampling.seed;
     }},
    {"--translation",
     [](const FleetOptions& g, FleetOptions& j) {
       j.pair.hypotheses.translation.method = g.pair.hypotheses.translation.method;
     }},
    {"--no-refine", [](const FleetOptions& g, FleetOptions& j) { j.pair.refine = g.pair.refine; }},
};

// merge's options for --out's map list only, and the job file's key that does their work.
const std::pair<const char*, const char*> kMapListOptions[] = {
    {"--reference", "its 'reference' key"},
    {"--topic", "each map entry's 'topic' key"},
    {"--tf-parent", "its 'tf_parent' key"},
    {"--tf-child", "its 'tf_child' key"}};

bool Given(const MergeCommand& command, const std::string& name) {
  return std::find(command.given.begin(), command.given.end(), name) != command.given.end();
}

Error RepeatedMap(const std::string& flag, const std::string& value, const std::string& name) {
  return Error(flag + " '" + value + "': map '" + name +
               "' is already given by --fixed or --initial-pose (a fixed map's pose is exact; it "
               "has no start pose)");
}

}  // namespace

Job JobFromMapList(const MergeCommand& command) {
  Job job = MapListJob(command.inputs, *command.out_dir, command.reference, command.options,
                       command.topics);
  job.tf_parent_frame = command.tf_parent_frame;
  job.tf_child_frame = command.tf_child_frame;
  std::vector<bool> given(job.maps.size(), false);  // by --fixed or --initial-pose
  for (const std::string& value : command.fixed_maps) {
    const MapPoseOption option = ParseMapPoseOption("--fixed", value, true, job);
    JobMap& map = job.maps[option.map];
    if (given[option.map]) throw RepeatedMap("--fixed", value, map.name);
    given[option.map] = true;
    map.fixed = true;
    if (!option.numbers.empty()) {
      map.T_merged_map = Pose2(option.numbers[0], option.numbers[1], option.numbers[2]);
    }
  }
  for (const std::string& value : command.initial_poses) {
    const MapPoseOption option = ParseMapPoseOption("--initial-pose", value, false, job);
    JobMap& map = job.maps[option.map];
    if (given[option.map]) throw RepeatedMap("--initial-pose", value, map.name);
    given[option.map] = true;
    PosePrior prior;
    prior.T_site_map = Pose2(option.numbers[0], option.numbers[1], option.numbers[2]);
    if (option.numbers.size() == 5) {
      prior.translation_sigma_m = option.numbers[3];
      prior.yaw_sigma_rad = option.numbers[4];
      if (!(prior.translation_sigma_m > 0.0) || !(prior.yaw_sigma_rad > 0.0)) {
        throw Error("--initial-pose '" + value + "': the sigmas (metres, radians) must be > 0");
      }
    }
    map.prior = prior;
  }
  if (const JobMap* first_fixed = FirstFixedMap(job.maps)) {
    if (command.reference && *command.reference != first_fixed->name) {
      throw Error("--reference '" + *command.reference + "': with fixed maps the reference is " +
                  "the first fixed map, '" + first_fixed->name + "'; leave --reference out");
    }
    job.reference = first_fixed->name;
  }
  return job;
}

void ApplyGivenOptions(const MergeCommand& command, const std::string& job_name,
                       FleetOptions& job) {
  for (const JobKeyOption& option : kJobKeyOptions) {
    if (Given(command, option.name)) option.copy(command.options, job);
  }
  if ((Given(command, "--octree-band-min") || Given(command, "--octree-band-max")) &&
      !(job.octree.band_min_m < job.octree.band_max_m)) {
    throw Error("--octree-band-min/--octree-band-max: job '" + job_name +
                "' gets the height band [" + std::to_string(job.octree.band_min_m) + ", " +
                std::to_string(job.octree.band_max_m) +
                "] m, which is empty; give both bounds, the lower below the upper");
  }
}

int RunJobs(const std::vector<Job>& jobs, bool quiet, std::ostream& out, std::ostream& err,
            bool force, double lock_wait_s) {
  int failed = 0;
  for (const Job& job : jobs) {
    try {
      RunAndPrintJob(job, quiet, force, lock_wait_s, out, err);
    } catch (const std::exception& e) {  // Error, filesystem_error, bad_alloc, cv::Exception
      ++failed;
      err << "fleetmerge: job '" << job.name << "' failed: " << e.what() << "\n";
    }
  }
  if (failed > 0) err << "fleetmerge: " << failed << " of " << jobs.size() << " job(s) failed\n";
  return failed > 0 ? 1 : 0;
}

int RunMergeCommand(const MergeCommand& command, std::ostream& out, std::ostream& err) {
  // An empty name would turn the cache off (even a job file's `cache:`) without a word.
  if (command.cache_dir && command.cache_dir->empty()) {
    throw Error("--cache: empty folder name; give a folder (--cache DIR), or leave --cache out");
  }
  std::vector<Job> jobs;
  if (command.out_dir) {
    jobs.push_back(JobFromMapList(command));
  } else {
    if (!command.fixed_maps.empty() || !command.initial_poses.empty()) {
      throw Error(std::string(command.fixed_maps.empty() ? "--initial-pose" : "--fixed") +
                  " names a map of --out's map list; a job file gives its maps' 'fixed', 'pose' "
                  "and 'initial_pose' keys itself (configs/README.md)");
    }
    for (const auto& [name, key] : kMapListOptions) {
      if (Given(command, name)) {
        throw Error(std::string(name) + " is for --out's map list; a job file sets it with " + key +
                    " (configs/README.md)");
      }
    }
    // Every job file is validated before any job runs.
    for (const auto& file : command.inputs) {
      for (Job& job : LoadJobFile(file)) jobs.push_back(std::move(job));
    }
    // The command line's options that job files' keys also set are every job's.
    for (Job& job : jobs) ApplyGivenOptions(command, job.name, job.options);
  }
  for (Job& job : jobs) {  // the command line's cache is every job's
    if (command.cache_dir) job.options.cache_dir = *command.cache_dir;
    if (command.cache_max_mb) job.options.cache_max_mb = *command.cache_max_mb;
    if (job.options.cache_dir.empty() && !job.cache_bound_without_cache.empty()) {
      throw Error(job.cache_bound_without_cache);
    }
  }
  const bool some_cache = std::any_of(
      jobs.begin(), jobs.end(), [](const Job& job) { return !job.options.cache_dir.empty(); });
  if (command.cache_max_mb && !some_cache) {
    throw Error("--cache-max-mb " + std::to_string(*command.cache_max_mb) +
                ": no job uses a cache; give --cache DIR (or a job file's 'cache:')");
  }
  return RunJobs(jobs, command.quiet, out, err, command.force, command.lock_wait_s);
}

}  // namespace fleetmerge
