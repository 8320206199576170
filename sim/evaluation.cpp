#include "sim/evaluation.hpp"

#include <algorithm>
#include <map>
#include <numeric>

#include "core/error.hpp"
#include "sim/ground_truth_pair.hpp"

namespace fleetmerge {
namespace {

// Report map index of every truth map, by name; both directions must match.
std::vector<int> MatchMaps(const MergeReport& report, const GroundTruth& truth,
                           const std::string& report_name, const std::string& truth_name) {
  std::map<std::string, int> in_report;
  for (std::size_t r = 0; r < report.maps.size(); ++r) {
    in_report[report.maps[r].name] = static_cast<int>(r);
  }
  std::vector<int> report_of;
  for (const TruthMap& map : truth.maps) {
    const auto it = in_report.find(map.name);
    if (it == in_report.end()) {
      throw Error("map '" + map.name + "' of " + truth_name + " is not in " + report_name);
    }
    report_of.push_back(it->second);
  }
  for (const ReportMap& map : report.maps) {
    const bool found = std::any_of(truth.maps.begin(), truth.maps.end(),
                                   [&](const TruthMap& t) { return t.name == map.name; });
    if (!found)
      throw Error("map '" + map.name + "' of " + report_name + " is not in " + truth_name);
  }
  return report_of;
}

int Find(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

double Median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

void Score(const MergeReport& report, const GroundTruth& truth, const OccupancyGrid& b, int ia,
           int ib, int ra, int rb, const EvalOptions& options, EvalPair& pair) {
  pair.merged = report.maps[ra].component == report.maps[rb].component;
  if (!pair.merged) return;
  const Pose2 T_a_b_est =
      report.maps[ra].T_component_map.inverse() * report.maps[rb].T_component_map;
  const Pose2 T_a_b_true = truth.maps[ia].T_building_map.inverse() * truth.maps[ib].T_building_map;
  const PoseError error = ComparePoses(b, T_a_b_est, T_a_b_true);
  pair.yaw_error_deg = error.yaw_deg;
  pair.displacement_cells = error.mean_displacement_cells;
  pair.translation_error_m = (T_a_b_est.translation_m() - T_a_b_true.translation_m()).norm();
  pair.coarse =
      error.yaw_deg <= options.coarse_yaw_deg && pair.displacement_cells <= options.coarse_cells;
  pair.fine =
      error.yaw_deg <= options.fine_yaw_deg && pair.displacement_cells <= options.fine_cells;
}

}  // namespace

Evaluation Evaluate(const MergeReport& report, const GroundTruth& truth,
                    const std::vector<const OccupancyGrid*>& maps, const EvalOptions& options,
                    const std::string& report_name, const std::string& truth_name) {
  if (maps.size() != truth.maps.size()) {
    throw Error("Evaluate: " + std::to_string(maps.size()) + " maps loaded for " +
                std::to_string(truth.maps.size()) + " in " + truth_name);
  }
  const std::vector<int> report_of = MatchMaps(report, truth, report_name, truth_name);
  const int n = static_cast<int>(truth.maps.size());
  std::map<std::string, int> index;
  for (int i = 0; i < n; ++i) index[truth.maps[i].name] = i;

  // Truly overlapping: connected by overlap edges of at least min_overlap_cells (LoadTruth
  // guarantees that both maps of an overlap exist and share a building).
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  std::map<std::pair<int, int>, long long> direct;
  for (const TruthOverlap& o : truth.overlaps) {
    const int a = index.at(o.a), b = index.at(o.b);
    direct[{std::min(a, b), std::max(a, b)}] = o.cells;
    if (o.cells >= options.min_overlap_cells) parent[Find(parent, a)] = Find(parent, b);
  }

  Evaluation result;
  std::vector<EvalPair> unscored;
  std::vector<int> partners(n, 0), merged_partners(n, 0);
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      const int ri = report_of[i], rj = report_of[j];
      const bool together = report.maps[ri].component == report.maps[rj].component;
      if (truth.maps[i].building != truth.maps[j].building) {
        if (together) {
          result.false_merges.push_back(
              {truth.maps[i].name, truth.maps[j].name, report.maps[ri].component});
        }
        continue;
      }
      EvalPair pair;
      pair.a = truth.maps[i].name;
      pair.b = truth.maps[j].name;
      pair.building = truth.maps[i].building;
      const auto it = direct.find({i, j});
      pair.overlap_cells = it == direct.end() ? 0 : it->second;
      pair.scored = Find(parent, i) == Find(parent, j);
      if (!pair.scored) {
        if (pair.overlap_cells > 0) unscored.push_back(pair);
        continue;
      }
      Score(report, truth, *maps[j], i, j, ri, rj, options, pair);
      ++partners[i], ++partners[j];
      if (pair.merged) ++merged_partners[i], ++merged_partners[j];
      result.pairs.push_back(pair);
    }
  }

  EvalSummary& s = result.summary;
  s.maps = n;
  s.components = static_cast<int>(report.components.size());
  std::vector<double> yaw, displacement;
  for (const EvalPair& p : result.pairs) {
    ++s.scored_pairs;
    s.merged_pairs += p.merged;
    s.coarse_pairs += p.coarse;
    s.fine_pairs += p.fine;
    if (p.merged) {
      yaw.push_back(p.yaw_error_deg);
      displacement.push_back(p.displacement_cells);
    }
  }
  s.coarse_rate = s.scored_pairs ? double(s.coarse_pairs) / s.scored_pairs : 1.0;
  s.fine_rate = s.scored_pairs ? double(s.fine_pairs) / s.scored_pairs : 1.0;
  s.false_merges = static_cast<int>(result.false_merges.size());
  for (int i = 0; i < n; ++i) {
    if (partners[i] > 0 && merged_partners[i] == 0) s.missed_maps.push_back(truth.maps[i].name);
  }
  s.median_yaw_error_deg = Median(yaw);
  s.median_displacement_cells = Median(displacement);
  if (!yaw.empty()) {
    s.max_yaw_error_deg = *std::max_element(yaw.begin(), yaw.end());
    s.max_displacement_cells = *std::max_element(displacement.begin(), displacement.end());
  }
  result.pairs.insert(result.pairs.end(), unscored.begin(), unscored.end());
  return result;
}

}  // namespace fleetmerge
