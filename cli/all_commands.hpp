// The whole `fleetmerge` command line: every subcommand, --help and --version. It is built into
// libfleetmerge_commands.so, which the executable loads for everything but `fleetmerge pair`
// (cli/main.cpp says why).
#pragma once

namespace fleetmerge {

// Parses argv and runs the command: the process exit code. Expects the process set up as
// cli/main.cpp does (allocator settings, OpenCV on the calling thread).
int RunAllCommands(int argc, char** argv);

}  // namespace fleetmerge

// The module's entry point (looked up by name with dlsym): RunAllCommands.
extern "C" __attribute__((visibility("default"))) int fleetmerge_run_all_commands(int argc,
                                                                                  char** argv);
