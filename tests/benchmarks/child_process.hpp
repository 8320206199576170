// Runs a program as a child process for the process-level benchmarks, and reports its peak
// resident memory (getrusage of the child, as /usr/bin/time -v reports it); and the main() those
// benchmarks share. Include only where FLEETMERGE_EXE is defined.
#pragma once

#include <benchmark/benchmark.h>
#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>

#include <cstdlib>
#include <string>
#include <vector>

extern char** environ;

namespace fleetmerge {

struct ChildRun {
  bool ok = false;           // started and exited with 0
  double peak_rss_mb = 0.0;  // the child's maximum resident set
};

// Runs `argv` with stdout and stderr on /dev/null.
inline ChildRun RunChild(const std::vector<std::string>& argv) {
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  pid_t pid = 0;
  const int error = posix_spawn(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ChildRun run;
  if (error != 0) return run;
  int status = 0;
  rusage usage{};
  if (wait4(pid, &status, 0, &usage) != pid) return run;
  run.ok = WIFEXITED(status) && WEXITSTATUS(status) == 0;
  run.peak_rss_mb = usage.ru_maxrss / 1024.0;  // kilobytes on Linux
  return run;
}

// main() of a benchmark of the fleetmerge executable: register_for(label, exe) registers its
// benchmarks for this build's executable ("current") and, with FLEETMERGE_BASELINE_EXE set, for
// that older one too ("baseline"), for a before/after comparison in one run.
inline int RunExecutableBenchmarks(int argc, char** argv,
                                   void (*register_for)(const std::string& label,
                                                        const std::string& exe)) {
  register_for("current", FLEETMERGE_EXE);
  if (const char* baseline = std::getenv("FLEETMERGE_BASELINE_EXE")) {
    register_for("baseline", baseline);
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

}  // namespace fleetmerge
