// `fleetmerge simulate OUT_DIR`: a multi-robot test case with a known answer (robot maps,
// truth.yaml, job.yaml), simulated in a building map or a synthetic office floor
// (sim/simulation.hpp), optionally with a robot from another building.
#pragma once

#include <CLI/App.hpp>
#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <optional>

#include "sim/simulation_options.hpp"

namespace fleetmerge {

struct SimulateCommand {
  std::filesystem::path out_dir;
  std::filesystem::path building_yaml;               // empty: a synthetic office floor
  std::optional<std::uint32_t> office_seed;          // default: options.seed
  std::filesystem::path foreign_yaml;                // a robot in this building as well
  std::optional<std::uint32_t> foreign_office_seed;  // ... or in this synthetic office
  SimulationOptions options;
};

// Registers the `simulate` subcommand and its options, filling `command` when parsed.
CLI::App* AddSimulateCommand(CLI::App& app, SimulateCommand& command);

// Loads the buildings, simulates, writes the case and prints what it wrote. Throws
// fleetmerge::Error for an unreadable map or a bad option value.
int RunSimulateCommand(const SimulateCommand& command, std::ostream& out);

}  // namespace fleetmerge
