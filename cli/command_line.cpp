#include "cli/command_line.hpp"

#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>

#include "core/error.hpp"
#include "fleetmerge/version.hpp"  // generated from project(VERSION) (api/CMakeLists.txt)

namespace fleetmerge {

std::string VersionLine() { return std::string("fleetmerge ") + FLEETMERGE_VERSION_STRING; }

void SetUpTopLevel(CLI::App& app) {
  app.description(
      "fleetmerge: merge the occupancy grid maps of a robot fleet (Carpin's Hough-spectrum "
      "method)");
  app.require_subcommand(1);
  app.set_version_flag("--version", VersionLine(), "print the version and exit");
}

std::optional<int> ParseCommandLine(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // CLI11 prints the message (or the help, or the version) and gives each kind of error a code
    // of its own (105, 106, 109, ...): one code, 2, for every wrong command line, as the
    // options' own checks below.
    return app.exit(e) == 0 ? 0 : 2;
  } catch (const Error& e) {  // thrown by option callbacks (e.g. a bad sampling spec)
    std::cerr << "fleetmerge: error: " << e.what() << "\n";
    return 2;
  }
  return std::nullopt;
}

int RunReportingErrors(const std::function<int()>& run) {
  try {
    return run();
  } catch (const Error& e) {
    std::cerr << "fleetmerge: error: " << e.what() << "\n";
  } catch (const std::filesystem::filesystem_error& e) {
    std::cerr << "fleetmerge: error: " << e.what() << "\n";
  }
  return 1;
}

}  // namespace fleetmerge
