// `fleetmerge eval report.json truth.yaml [--json] [--min-overlap-cells N]`: scores a merge
// (sim/evaluation.hpp) and prints a table, or JSON for tools. Exit code 0 whenever it
// evaluated, whatever the score; bad input throws fleetmerge::Error (exit 1).
#pragma once

#include <filesystem>
#include <iosfwd>
#include <nlohmann/json_fwd.hpp>

#include "sim/evaluation.hpp"

namespace fleetmerge {

struct EvalCommand {
  std::filesystem::path report_json;
  std::filesystem::path truth_yaml;
  bool json = false;
  EvalOptions options;
};

// The evaluation as JSON: {report, truth, min_overlap_cells, summary{...}, pairs[...],
// false_merges[...]}.
nlohmann::json EvaluationJson(const EvalCommand& command, const Evaluation& evaluation);

int RunEvalCommand(const EvalCommand& command, std::ostream& out);

}  // namespace fleetmerge
