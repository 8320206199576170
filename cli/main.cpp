// The `fleetmerge` executable. `fleetmerge pair` runs here; every other command, --help and
// --version run in libfleetmerge_commands.so (cli/all_commands.hpp), loaded when needed.
//
// Why two parts: the executable is linked --as-needed, so it loads only what the pair path uses
// (yaml-cpp, libspng, zlib, TBB; OpenCV core is linked in from its static archive,
// cli/CMakeLists.txt). The rest of the tool also loads OpenCV's imgproc
// (the simulator), Ceres' sparse solvers with glog, BLAS and LAPACK (the pose graph) and OctoMap:
// ~8 ms more start-up on the CI machine, a fifth of a pair process (docs/speed.md, "Where the
// time goes now"). Any other command loads the same libraries as one executable would, plus the
// module: `fleetmerge --help` takes 0.3-0.5 ms longer than it did as one executable.
#include <CLI/CLI.hpp>
#include <iostream>
#include <string_view>

#include "cli/command_line.hpp"
#include "cli/commands_module.hpp"
#include "cli/pair_command.hpp"
#include "cli/process_memory.hpp"
#include "cli/process_threads.hpp"

namespace {

// `fleetmerge pair ...`: the same subcommand, options and messages as in the full command line.
int RunPair(int argc, char** argv) {
  using namespace fleetmerge;
  CLI::App app;
  SetUpTopLevel(app);
  PairCommand pair;
  AddPairCommand(app, pair);
  if (const std::optional<int> exit_code = ParseCommandLine(app, argc, argv)) return *exit_code;
  return RunReportingErrors([&] {
    ShareTheHeapBetweenThreads();
    return RunPairCommand(pair, std::cout);
  });
}

}  // namespace

int main(int argc, char** argv) {
  using namespace fleetmerge;
  KeepFreedMemoryForReuse();
  RunOpenCvOnTheCallingThread();
  if (argc >= 2 && std::string_view(argv[1]) == "pair") return RunPair(argc, argv);
  return RunThroughCommandsModule(argc, argv);
}
