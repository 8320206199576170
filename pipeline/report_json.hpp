// report.json of a fleet-merging job. Other tools read it: the names below are fixed
// (fields may be added):
//   maps[]: name, source, component, pose {x, y, yaw} (the map frame in its component's merged
//           frame; the component's reference map has the identity, a fixed map its given
//           pose; with priors, the site frame's), fixed (a base map that never moves: the
//           job's `fixed`), placed_by ("fixed", "reference", "pairs", "prior" or "unmerged":
//           pipeline/fleet_graph.hpp, PlacedBy), initial_pose {x, y, yaw} and
//           initial_pose_sigma [m, rad] (a map with a known start pose)
//   components[]: id, maps (names), merged_map (file name; absent for an unmerged map)
//   pairs[]: a, b, omega (best), accepted, overlap_cells, wall_agreement (best), ambiguous,
//            margin (nats; null without a runner-up: core/pose_evidence.hpp), hypotheses [{x,
//            y, yaw, omega, overlap_cells, wall_agreement}] (b's frame in a's, best first),
//            edge_hypothesis (accepted), dropped_by_priors [{x, y, yaw, omega,
//            overlap_cells, wall_agreement, search_rank, sigmas}] (hypotheses the known start
//            poses dropped, pipeline/pose_priors.hpp), note (why rejected or replaced; a pair
//            whose best passes the thresholds but whose hypotheses all contradict the priors:
//            "refused: ...")
//   timing_ms: load, pairs, refine, composite, write, total; report_html (writing report.html,
//              pipeline/html_report.hpp: its map images, made while the merged maps are
//              written, and its page, after `total` was taken) when the set is written
// Jobs with octrees add (pipeline/octree_maps.hpp, AddOctreesToReport): maps[].pose.z and
// maps[].floor_z for octree maps, components[].merged_octree, timing_ms.octree_projection and
// octree_write.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "job/job.hpp"
#include "pipeline/fleet_merge.hpp"

namespace fleetmerge {

struct JobTiming {
  double load_ms = 0.0, write_ms = 0.0, total_ms = 0.0;
};

// {x, y, yaw} (metres, radians), as every pose in report.json.
nlohmann::json PoseJson(const Pose2& T);
// A pair's hypotheses as report.json and `pair --json` give them.
nlohmann::json HypothesesJson(const std::vector<PairHypothesis>& hypotheses);
// The ranking margin: null when there is no runner-up (infinite).
nlohmann::json MarginJson(double margin_nats);

// merged_files[c]: the merged map's file name of component c, empty when it has none.
nlohmann::json MakeReport(const Job& job, const FleetResult& result,
                          const std::vector<std::string>& merged_files, const JobTiming& timing);

}  // namespace fleetmerge
