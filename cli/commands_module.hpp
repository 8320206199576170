// Loading libfleetmerge_commands.so (cli/all_commands.hpp) into the executable.
#pragma once

namespace fleetmerge {

// Loads the module and runs the command line through it: the process exit code, or 1 with a
// message naming the folders searched when the module cannot be found or loaded. Searched in
// order: the executable's folder (the build tree), the install folder relative to it (a
// relocated install: FLEETMERGE_COMMANDS_RELATIVE_DIR), the configured install folder
// (FLEETMERGE_COMMANDS_INSTALL_DIR).
int RunThroughCommandsModule(int argc, char** argv);

}  // namespace fleetmerge
