// What the executable's own `pair` and the full command line (cli/all_commands.hpp) share: the
// top-level app with its description and --version, parsing, and how a command's errors are
// reported.
#pragma once

#include <CLI/App.hpp>
#include <functional>
#include <optional>
#include <string>

namespace fleetmerge {

// "fleetmerge <version>": what --version and `fleetmerge version` print.
std::string VersionLine();

// The description, one subcommand required, --version.
void SetUpTopLevel(CLI::App& app);

// Parses the command line: the exit code to leave with (2 for a wrong command line: a parse
// error or a bad option value; 0 for --help and --version), or nothing when a command is to run.
std::optional<int> ParseCommandLine(CLI::App& app, int argc, char** argv);

// Runs a command: its exit code, or 1 after "fleetmerge: error: ..." on stderr for bad input.
int RunReportingErrors(const std::function<int()>& run);

}  // namespace fleetmerge
