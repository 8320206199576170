#include "cli/merge_command.hpp"

#include <unistd.h>

#include <cstdio>
#include <exception>
#include <ostream>

#include "core/error.hpp"
#include "io/job_file.hpp"
#include "io/map_inputs.hpp"
#include "pipeline/job_run.hpp"

namespace fleetmerge {
namespace {

// A bar redrawn in place on a terminal; otherwise a line per stage about every quarter of its
// work and at its end.
ProgressFn MakeProgress(const std::string& job, bool quiet, std::ostream& err) {
  if (quiet) return {};
  const bool terminal = isatty(fileno(stderr)) != 0;
  return [job, terminal, &err](const std::string& stage, int done, int total) {
    if (terminal) {
      const int width = 30, filled = total > 0 ? width * done / total : width;
      err << "\r" << job << " " << stage << " [" << std::string(filled, '#')
          << std::string(width - filled, ' ') << "] " << done << "/" << total
          << (done == total ? "\n" : "") << std::flush;
    } else if (done == total || (total >= 4 && done % ((total + 3) / 4) == 0)) {
      err << job << ": " << stage << " " << done << "/" << total << "\n" << std::flush;
    }
  };
}

// Runs one job (pipeline/job_run.hpp) and prints its one-line summary.
void RunAndPrintJob(const Job& job, bool quiet, bool force, std::ostream& out, std::ostream& err) {
  JobRunOptions options;
  options.force = force;
  options.progress = MakeProgress(job.name, quiet, err);
  const JobOutcome outcome = RunJob(job, options);
  const FleetResult& result = outcome.result;
  int merged = 0;
  for (const auto& c : result.components) merged += c.merged.has_value();
  out << job.name << ": " << job.maps.size() << " maps, " << result.components.size()
      << " component(s), " << merged
      << " merged map(s); report: " << (job.output_dir / "report.json").string() << " ("
      << static_cast<int>(outcome.report["timing_ms"]["total"].get<double>()) << " ms)\n";
}

}  // namespace

Job JobFromMapList(const MergeCommand& command) {
  Job job;
  job.name = "merge";
  job.output_dir = *command.out_dir;
  job.options = command.options;
  std::vector<MapInput> inputs;
  for (const auto& path : command.inputs) inputs.push_back({path, path, "", command.topics});
  job.maps = ExpandMapInputs(inputs);
  job.tf_parent_frame = command.tf_parent_frame;
  job.tf_child_frame = command.tf_child_frame;
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
      RunAndPrintJob(job, quiet, force, out, err);
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
    if (!command.topics.empty()) {
      throw Error("--topic is for maps given with --out; in a job file give a map entry's 'topic'");
    }
    // Every job file is validated before any job runs.
    for (const auto& file : command.inputs) {
      for (Job& job : LoadJobFile(file)) jobs.push_back(std::move(job));
    }
  }
  return RunJobs(jobs, command.quiet, out, err, command.force);
}

}  // namespace fleetmerge
