#include "cli/demo_command.hpp"

#include <CLI/CLI.hpp>
#include <chrono>
#include <fstream>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include "cli/eval_command.hpp"
#include "cli/merge_command.hpp"
#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "io/job_file.hpp"
#include "io/map_io.hpp"
#include "io/simulated_case_file.hpp"
#include "core/parallel.hpp"
#include "sim/simulation.hpp"

namespace fleetmerge {
namespace {

namespace fs = std::filesystem;

// Makes room for DIR/case. Only a previous demo's case (truth.yaml and job.yaml, as
// WriteSimulatedCase leaves them) is removed; anything else there belongs to the user and stops
// the demo before it writes a byte.
void PrepareCaseDir(const fs::path& out_dir, const fs::path& case_dir) {
  const std::string advice = "; choose another --out or remove it yourself";
  std::error_code ec;
  const fs::file_status status = fs::symlink_status(case_dir, ec);
  if (!fs::exists(status)) {
    if (fs::exists(out_dir / "evaluation.json")) {
      throw Error((out_dir / "evaluation.json").string() +
                  " exists but no demo case is beside it (" + case_dir.string() +
                  "); refusing to overwrite it" + advice);
    }
    return;
  }
  if (!fs::is_directory(status)) {
    throw Error(case_dir.string() + " exists and is not a folder; refusing to replace it" + advice);
  }
  if (fs::is_empty(case_dir)) return;
  if (!fs::is_regular_file(case_dir / "truth.yaml") ||
      !fs::is_regular_file(case_dir / "job.yaml")) {
    throw Error(case_dir.string() +
                " exists and does not hold a previous demo (no truth.yaml and job.yaml); "
                "refusing to delete it" +
                advice);
  }
  fs::remove_all(case_dir);
}

// Runs `fleetmerge eval` on the merge into a string (JSON or the table).
std::string EvaluationText(EvalCommand command, bool json) {
  command.json = json;
  std::ostringstream text;
  RunEvalCommand(command, text);
  return text.str();
}

// What the evaluation found wrong, empty when every truly overlapping pair is merged within the
// coarse tolerance, nothing is merged falsely and no map is missed.
std::string EvaluationFailures(const nlohmann::json& evaluation) {
  const nlohmann::json& s = evaluation.at("summary");
  std::ostringstream failures;
  const int scored = s.at("scored_pairs"), coarse = s.at("coarse_pairs");
  if (coarse < scored) {
    failures << " " << scored - coarse << " of " << scored
             << " truly overlapping pair(s) not merged within the coarse tolerance;";
  }
  if (s.at("false_merges").get<int>() > 0)
    failures << " " << s.at("false_merges") << " false merge(s);";
  if (!s.at("missed_maps").empty())
    failures << " missed maps " << s.at("missed_maps").dump() << ";";
  return failures.str();
}

void PrintOutputs(const Job& job, const fs::path& truth_yaml, const fs::path& evaluation_json,
                  std::ostream& out) {
  const fs::path report_json = job.output_dir / "report.json";
  // The merged maps' file names are in report.json only (io/report_file reads poses, not them);
  // `eval` has checked the file already.
  std::ifstream in(report_json, std::ios::binary);
  const nlohmann::json report = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
  if (!report.is_object() || !report.contains("components")) {
    throw Error(report_json.string() + ": cannot read its components");
  }
  out << "\noutputs:\n";
  bool any_merged = false;
  for (const nlohmann::json& component : report.at("components")) {
    if (!component.contains("merged_map")) continue;
    any_merged = true;
    const fs::path yaml = job.output_dir / component.at("merged_map").get<std::string>();
    const LoadedMap merged = LoadMap(yaml);  // checks what we point the user to
    const fs::path preview = job.output_dir / (yaml.stem().string() + "_preview.png");
    out << "  merged map YAML: " << yaml.string() << "\n"
        << "  merged map PGM: " << merged.metadata.image_path.string() << "\n"
        << "  preview PNG: " << preview.string() << "\n";
  }
  if (!any_merged) out << "  (no merged map: no two maps were merged)\n";
  out << "  report: " << report_json.string() << "\n"
      << "  report page: " << (job.output_dir / "report.html").string() << "\n"
      << "  evaluation: " << evaluation_json.string() << "\n"
      << "  truth: " << truth_yaml.string() << "\n";
}

}  // namespace

CLI::App* AddDemoCommand(CLI::App& app, DemoCommand& c) {
  CLI::App* demo = app.add_subcommand(
      "demo", "Simulate a robot fleet in a synthetic office, merge its maps, evaluate the merge");
  demo->add_option("--out", c.out_dir, "output folder (the case goes to DIR/case)")
      ->capture_default_str();
  demo->add_option("--seed", c.seed, "random seed (office floor and robots)")
      ->capture_default_str();
  demo->add_option("--robots", c.robots, "robots in the office")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  return demo;
}

int RunDemoCommand(const DemoCommand& c, std::ostream& out, std::ostream& err) {
  const auto start = std::chrono::steady_clock::now();
  SimulationOptions options;
  options.seed = c.seed;
  options.robots = c.robots;
  ValidateSimulationOptions(options);
  const fs::path case_dir = c.out_dir / "case";
  PrepareCaseDir(c.out_dir, case_dir);

  const SimulatedCase simulated = SimulateFleet(OfficeBuilding(c.seed), options);
  const WrittenCase written = WriteSimulatedCase(simulated, case_dir);
  out << "simulated " << simulated.maps.size() << " robots in synthetic office " << c.seed << ": "
      << case_dir.string() << "\n";

  const std::vector<Job> jobs = LoadJobFile(written.job_yaml);
  if (jobs.size() != 1) throw Error(written.job_yaml.string() + ": expected one job");
  if (RunJobs(jobs, /*quiet=*/false, out, err) != 0) {
    throw Error("the merge of " + written.job_yaml.string() + " failed (see above)");
  }

  EvalCommand eval;
  eval.report_json = jobs.front().output_dir / "report.json";
  eval.truth_yaml = written.truth_yaml;
  const std::string evaluation_text = EvaluationText(eval, /*json=*/true);
  const fs::path evaluation_json = c.out_dir / "evaluation.json";
  WriteFileAtomically(evaluation_json, evaluation_text);
  out << "\n" << EvaluationText(eval, /*json=*/false);
  const std::string failures = EvaluationFailures(nlohmann::json::parse(evaluation_text));
  if (failures.empty()) {
    out << "\nevaluation: OK: every truly overlapping pair merged within the coarse tolerance, no "
           "false merge, no missed map\n";
  } else {
    out << "\nevaluation: FAILED:" << failures << "\n";
  }

  PrintOutputs(jobs.front(), written.truth_yaml, evaluation_json, out);
  out << std::fixed << std::setprecision(1) << "\ntotal time " << MillisecondsSince(start) / 1000.0
      << " s\n";
  out.unsetf(std::ios::fixed);
  return 0;
}

}  // namespace fleetmerge
