#include "pipeline/report_json.hpp"

#include <cmath>

namespace fleetmerge {
nlohmann::json PoseJson(const Pose2& T) {
  return {{"x", T.x_m()}, {"y", T.y_m()}, {"yaw", T.yaw_rad()}};
}

namespace {

nlohmann::json PairJson(const Job& job, const PairOutcome& p) {
  nlohmann::json j = {{"a", job.maps[p.a].name},
                      {"b", job.maps[p.b].name},
                      {"omega", p.best_omega()},
                      {"accepted", p.accepted},
                      {"hypotheses", HypothesesJson(p.hypotheses)},
                      {"overlap_cells", p.overlap_cells},
                      {"wall_agreement", p.wall_agreement},
                      {"ambiguous", p.ambiguous},
                      {"margin", MarginJson(p.margin_nats)}};
  if (p.accepted) j["edge_hypothesis"] = p.edge_hypothesis;
  if (!p.dropped_by_priors.empty()) {
    nlohmann::json& dropped = j["dropped_by_priors"] = nlohmann::json::array();
    for (const PairOutcome::Dropped& d : p.dropped_by_priors) {
      nlohmann::json h = HypothesesJson({d.hypothesis}).front();
      h["search_rank"] = d.search_rank;
      h["sigmas"] = d.sigmas;
      dropped.push_back(h);
    }
  }
  if (!p.note.empty()) j["note"] = p.note;
  return j;
}

}  // namespace

nlohmann::json HypothesesJson(const std::vector<PairHypothesis>& hypotheses) {
  nlohmann::json out = nlohmann::json::array();
  for (const PairHypothesis& h : hypotheses) {
    nlohmann::json j = PoseJson(h.T_a_b);
    j["omega"] = h.omega;
    j["overlap_cells"] = h.overlap_cells;
    j["wall_agreement"] = h.wall_agreement;
    out.push_back(j);
  }
  return out;
}

nlohmann::json MarginJson(double margin_nats) {
  return std::isfinite(margin_nats) ? nlohmann::json(margin_nats) : nlohmann::json(nullptr);
}

nlohmann::json MakeReport(const Job& job, const FleetResult& result,
                          const std::vector<std::string>& merged_files, const JobTiming& timing) {
  nlohmann::json report;
  report["job"] = job.name;
  report["resolution"] = result.resolution_m;
  report["maps"] = nlohmann::json::array();
  for (std::size_t m = 0; m < job.maps.size(); ++m) {
    nlohmann::json map = {{"name", job.maps[m].name},
                          {"source", job.maps[m].source.generic_string()},
                          {"component", result.component_of[m]},
                          {"pose", PoseJson(result.T_component_map[m])},
                          {"fixed", job.maps[m].fixed},
                          {"placed_by", PlacedByName(result.placed_by[m])}};
    if (const auto& prior = job.maps[m].prior) {
      map["initial_pose"] = PoseJson(prior->T_site_map);
      map["initial_pose_sigma"] = {prior->translation_sigma_m, prior->yaw_sigma_rad};
    }
    report["maps"].push_back(map);
  }
  report["components"] = nlohmann::json::array();
  for (std::size_t c = 0; c < result.components.size(); ++c) {
    nlohmann::json names = nlohmann::json::array();
    for (int m : result.components[c].maps) names.push_back(job.maps[m].name);
    nlohmann::json j = {
        {"id", c}, {"maps", names}, {"reference", job.maps[result.components[c].reference].name}};
    if (!merged_files[c].empty()) j["merged_map"] = merged_files[c];
    report["components"].push_back(j);
  }
  report["pairs"] = nlohmann::json::array();
  for (const auto& p : result.pairs) report["pairs"].push_back(PairJson(job, p));
  report["timing_ms"] = {{"load", timing.load_ms},
                         {"pairs", result.timing.pairs_ms},
                         {"refine", result.timing.refine_ms},
                         {"composite", result.timing.composite_ms},
                         {"write", timing.write_ms},
                         {"total", timing.total_ms}};
  return report;
}

}  // namespace fleetmerge
