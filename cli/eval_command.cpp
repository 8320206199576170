#include "cli/eval_command.hpp"

#include <iomanip>
#include <nlohmann/json.hpp>
#include <ostream>

#include "io/map_io.hpp"
#include "io/report_file.hpp"
#include "io/truth_file.hpp"

namespace fleetmerge {
namespace {

void PrintTable(const EvalCommand& command, const Evaluation& e, std::ostream& out) {
  out << "report " << command.report_json.string() << " against " << command.truth_yaml.string()
      << " (scored: pairs linked by overlaps of >= " << command.options.min_overlap_cells
      << " cells, directly or through other maps)\n";
  out << std::left << std::setw(28) << "pair" << std::setw(14) << "building" << std::right
      << std::setw(9) << "overlap" << std::setw(8) << "merged" << std::setw(11) << "yaw[deg]"
      << std::setw(10) << "trans[m]" << std::setw(11) << "displ[c]" << std::setw(8) << "coarse"
      << std::setw(6) << "fine"
      << "\n";
  for (const EvalPair& p : e.pairs) {
    out << std::left << std::setw(28) << (p.a + " - " + p.b) << std::setw(14) << p.building
        << std::right << std::setw(9) << p.overlap_cells;
    if (!p.scored) {
      out << "  (not linked by overlaps: not scored)\n";
      continue;
    }
    out << std::setw(8) << (p.merged ? "yes" : "NO");
    if (p.merged) {
      out << std::fixed << std::setprecision(3) << std::setw(11) << p.yaw_error_deg << std::setw(10)
          << p.translation_error_m << std::setprecision(2) << std::setw(11) << p.displacement_cells
          << std::setw(8) << (p.coarse ? "ok" : "FAIL") << std::setw(6) << (p.fine ? "ok" : "FAIL");
      out.unsetf(std::ios::fixed);
    } else {
      out << std::setw(11) << "-" << std::setw(10) << "-" << std::setw(11) << "-" << std::setw(8)
          << "FAIL" << std::setw(6) << "FAIL";
    }
    out << "\n";
  }
  const EvalSummary& s = e.summary;
  out << std::fixed << std::setprecision(1);
  out << "\n"
      << s.maps << " maps, " << s.components << " component(s); " << s.scored_pairs
      << " truly overlapping pair(s), " << s.merged_pairs << " merged\n";
  out << "success coarse (" << command.options.coarse_yaw_deg << " deg, "
      << command.options.coarse_cells << " cells): " << s.coarse_pairs << "/" << s.scored_pairs
      << " = " << 100.0 * s.coarse_rate << " %\n";
  out << std::setprecision(2) << "success fine (" << command.options.fine_yaw_deg << " deg, "
      << command.options.fine_cells << " cells): " << s.fine_pairs << "/" << s.scored_pairs << " = "
      << std::setprecision(1) << 100.0 * s.fine_rate << " %\n";
  out << std::setprecision(3) << "merged pairs: median yaw error " << s.median_yaw_error_deg
      << " deg (max " << s.max_yaw_error_deg << "), median displacement "
      << s.median_displacement_cells << " cells (max " << s.max_displacement_cells << ")\n";
  out << "false merges: " << s.false_merges;
  for (const EvalFalseMerge& f : e.false_merges) {
    out << (&f == &e.false_merges.front() ? " (" : ", ") << f.a << " + " << f.b << " in component "
        << f.component;
  }
  out << (e.false_merges.empty() ? "" : ")") << "\n";
  out << "missed maps: " << s.missed_maps.size();
  for (const std::string& name : s.missed_maps) {
    out << (&name == &s.missed_maps.front() ? " (" : ", ") << name;
  }
  out << (s.missed_maps.empty() ? "" : ")") << "\n";
  out.unsetf(std::ios::fixed);
}

}  // namespace

nlohmann::json EvaluationJson(const EvalCommand& command, const Evaluation& e) {
  nlohmann::json pairs = nlohmann::json::array();
  for (const EvalPair& p : e.pairs) {
    nlohmann::json j = {{"a", p.a},
                        {"b", p.b},
                        {"building", p.building},
                        {"overlap_cells", p.overlap_cells},
                        {"scored", p.scored},
                        {"merged", p.merged}};
    if (p.merged && p.scored) {
      j["yaw_error_deg"] = p.yaw_error_deg;
      j["translation_error_m"] = p.translation_error_m;
      j["displacement_cells"] = p.displacement_cells;
    }
    if (p.scored) {
      j["coarse"] = p.coarse;
      j["fine"] = p.fine;
    }
    pairs.push_back(j);
  }
  nlohmann::json false_merges = nlohmann::json::array();
  for (const EvalFalseMerge& f : e.false_merges) {
    false_merges.push_back({{"a", f.a}, {"b", f.b}, {"component", f.component}});
  }
  const EvalSummary& s = e.summary;
  const nlohmann::json summary = {{"maps", s.maps},
                                  {"components", s.components},
                                  {"scored_pairs", s.scored_pairs},
                                  {"merged_pairs", s.merged_pairs},
                                  {"coarse_pairs", s.coarse_pairs},
                                  {"fine_pairs", s.fine_pairs},
                                  {"coarse_rate", s.coarse_rate},
                                  {"fine_rate", s.fine_rate},
                                  {"false_merges", s.false_merges},
                                  {"missed_maps", s.missed_maps},
                                  {"median_yaw_error_deg", s.median_yaw_error_deg},
                                  {"max_yaw_error_deg", s.max_yaw_error_deg},
                                  {"median_displacement_cells", s.median_displacement_cells},
                                  {"max_displacement_cells", s.max_displacement_cells}};
  return {{"report", command.report_json.generic_string()},
          {"truth", command.truth_yaml.generic_string()},
          {"min_overlap_cells", command.options.min_overlap_cells},
          {"tolerances",
           {{"coarse_yaw_deg", command.options.coarse_yaw_deg},
            {"coarse_cells", command.options.coarse_cells},
            {"fine_yaw_deg", command.options.fine_yaw_deg},
            {"fine_cells", command.options.fine_cells}}},
          {"summary", summary},
          {"pairs", pairs},
          {"false_merges", false_merges}};
}

int RunEvalCommand(const EvalCommand& command, std::ostream& out) {
  const GroundTruth truth = LoadTruth(command.truth_yaml);
  const MergeReport report = LoadMergeReport(command.report_json);
  std::vector<OccupancyGrid> grids;
  for (const TruthMap& map : truth.maps) grids.push_back(LoadMap(map.file).grid);
  std::vector<const OccupancyGrid*> pointers;
  for (const OccupancyGrid& grid : grids) pointers.push_back(&grid);
  const Evaluation evaluation = Evaluate(report, truth, pointers, command.options,
                                         command.report_json.string(), command.truth_yaml.string());
  if (command.json) {
    out << EvaluationJson(command, evaluation).dump(2) << "\n";
  } else {
    PrintTable(command, evaluation, out);
  }
  return 0;
}

}  // namespace fleetmerge
