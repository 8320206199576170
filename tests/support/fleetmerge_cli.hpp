// The fleetmerge executable for CLI tests: its path comes from the test target's
// FLEETMERGE_EXECUTABLE definition ($<TARGET_FILE:fleetmerge>).
#pragma once

#include <string>

#include "tests/support/run_command.hpp"

#ifndef FLEETMERGE_EXECUTABLE
#error "a CLI test target needs FLEETMERGE_EXECUTABLE defined (see tests/pipeline/CMakeLists.txt)"
#endif

namespace fleetmerge::testing {

// Runs `fleetmerge <args>` through the shell (args are quoted by the caller, ShellQuote).
inline CommandResult Fleetmerge(const std::string& args) {
  return RunCommand(std::string(FLEETMERGE_EXECUTABLE) + " " + args);
}

}  // namespace fleetmerge::testing
