// `fleetmerge pair A.yaml B.yaml`: loads two maps, runs the pair job (pipeline/pair_merge.hpp),
// prints the ranked hypotheses (text or JSON) and optionally writes the merged map of the best.
#pragma once

#include <filesystem>
#include <iosfwd>
#include <optional>

#include "pipeline/pair_merge.hpp"

namespace fleetmerge {

struct PairCommand {
  std::filesystem::path a_yaml;
  std::filesystem::path b_yaml;
  int hypotheses = 4;  // -n
  bool json = false;
  std::optional<std::filesystem::path> out_dir;
  PairOptions options;
};

// Returns the process exit code; throws fleetmerge::Error for bad input.
int RunPairCommand(const PairCommand& command, std::ostream& out);

}  // namespace fleetmerge
