// Ground-truth test pairs cut from one real map: two overlapping parts, the second re-framed by a
// known rigid motion and resampled onto a grid of its own, as a second robot would have built it.
#pragma once

#include <random>
#include <vector>

#include "core/occupancy_grid.hpp"
#include "core/pose2.hpp"

namespace fleetmerge {

struct CutPairOptions {
  double min_overlap = 0.35;  // share of the known extent along the split axis seen by both
  double max_overlap = 0.6;
  double max_offset_m = 20.0;  // |translation| of b's frame in a's frame, per axis
};

struct GroundTruthPair {
  OccupancyGrid a;  // map frame = the source map's frame
  OccupancyGrid b;  // map frame = T_a_b applied to a's frame
  Pose2 T_a_b;      // truth: pose of b's map frame in a's map frame
};

// Splits `building`'s known bounding box along a random axis into two parts overlapping by a
// random share; part b gets a map frame at pose (random translation, yaw_rad) and an
// axis-aligned grid in that frame (nearest-cell resampling).
GroundTruthPair CutPair(const OccupancyGrid& building, double yaw_rad, std::mt19937& rng,
                        const CutPairOptions& options = {});

// The part re-framed: its map frame moves to T_map_new (given in the part's map frame), on an
// axis-aligned grid in that frame covering the part (nearest-cell resampling).
OccupancyGrid Reframe(const OccupancyGrid& part, const Pose2& T_map_new);

struct CutFleetOptions {
  double overlap = 0.3;        // each tile grows by this share of a tile on every side
  double max_offset_m = 20.0;  // |translation| of each map frame, per axis
};

struct GroundTruthFleet {
  std::vector<OccupancyGrid> maps;    // one per robot, each in a random frame of its own
  std::vector<Pose2> T_building_map;  // truth: each map's frame in the building's frame
};

// K robots' maps: overlapping tiles of `building`'s known box (a near-square grid of tiles),
// each re-framed by a random rotation (any angle) and translation.
GroundTruthFleet CutFleet(const OccupancyGrid& building, int robots, std::mt19937& rng,
                          const CutFleetOptions& options = {});

// Frame-independent pose error of an estimate of T_a_b: yaw error, and the mean displacement
// of b's occupied cells between the estimate and the truth, in cells.
struct PoseError {
  double yaw_deg = 0.0;
  double mean_displacement_cells = 0.0;
};
PoseError ComparePoses(const OccupancyGrid& b, const Pose2& T_a_b_estimate,
                       const Pose2& T_a_b_true);

}  // namespace fleetmerge
