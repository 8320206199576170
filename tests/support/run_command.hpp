// Running a command line from a test (the `fleetmerge` executable end to end): exit code, and
// standard output and standard error kept apart, so that a test can parse one (JSON on stdout)
// and search the other (messages, progress lines). Neither stream is a terminal.
#pragma once

#include <filesystem>
#include <string>

namespace fleetmerge::testing {

struct CommandResult {
  int exit_code = -1;  // -1 when the command could not be run or was killed by a signal
  std::string out;     // standard output
  std::string err;     // standard error
  std::string both() const { return out + err; }
};

// Runs `command` through /bin/sh. Standard error goes to a temporary file read afterwards, so a
// command writing a lot to both streams cannot block on a full pipe.
CommandResult RunCommand(const std::string& command);

// `text` as one single-quoted shell word (for paths in a command line).
std::string ShellQuote(const std::string& text);
inline std::string ShellQuote(const std::filesystem::path& path) {
  return ShellQuote(path.string());
}

}  // namespace fleetmerge::testing
