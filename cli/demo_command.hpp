// `fleetmerge demo [--out DIR] [--seed S] [--robots K]`: the README's main command, end to end
// with nothing to supply. It simulates K robots in the synthetic office floor of seed S
// (sim/simulation.hpp) and writes the case to DIR/case (robot maps, truth.yaml, job.yaml),
// runs the case's job (cli/merge_command.hpp), scores the merge against the truth
// (cli/eval_command.hpp) into DIR/evaluation.json, prints the evaluation table, where each
// output is and the total time.
#pragma once

#include <CLI/App.hpp>
#include <cstdint>
#include <filesystem>
#include <iosfwd>

namespace fleetmerge {

struct DemoCommand {
  std::filesystem::path out_dir = "out/demo";  // relative to the current folder
  std::uint32_t seed = 1;
  int robots = 4;
};

// Registers the `demo` subcommand and its options, filling `command` when parsed.
CLI::App* AddDemoCommand(CLI::App& app, DemoCommand& command);

// Runs the demo. Rerunning over a DIR of an earlier demo replaces DIR/case; a DIR/case that
// exists without a demo's truth.yaml and job.yaml (or a DIR/evaluation.json beside no demo case)
// is refused with fleetmerge::Error before anything is written, so no other file is ever deleted.
// Returns 0 when the demo ran, whatever the evaluation says (failures are printed); a merge that
// fails or any bad input throws fleetmerge::Error.
int RunDemoCommand(const DemoCommand& command, std::ostream& out, std::ostream& err);

}  // namespace fleetmerge
