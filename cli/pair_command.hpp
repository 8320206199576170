// `fleetmerge pair A.yaml B.yaml`: loads two maps, runs the pair job (pipeline/pair_merge.hpp),
// prints the ranked hypotheses (text or JSON) and optionally writes the merged map of the best.
#pragma once

#include <CLI/App.hpp>
#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "pipeline/pair_merge.hpp"

namespace fleetmerge {

struct PairCommand {
  std::filesystem::path a_yaml;  // a map YAML or a bag
  std::filesystem::path b_yaml;
  std::vector<std::string> topics;  // bags: the map topic to read (each input needs exactly one)
  int hypotheses = 4;               // -n
  int threads = 0;                  // --threads: shared by the pair's work (0: all cores)
  bool json = false;
  std::optional<std::filesystem::path> out_dir;
  PairOptions options;
};

// The `pair` subcommand of `app` with its options, filling `command`.
CLI::App* AddPairCommand(CLI::App& app, PairCommand& command);

// Returns the process exit code; throws fleetmerge::Error for bad input.
int RunPairCommand(const PairCommand& command, std::ostream& out);

}  // namespace fleetmerge
