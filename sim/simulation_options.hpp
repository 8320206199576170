// Options of the fleet simulator (sim/simulation.hpp), with their defaults. Lengths in
// metres, angles in degrees where a user types them, as on the command line.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "job/pose_prior.hpp"

namespace fleetmerge {

struct LidarOptions {
  int beams = 360;              // evenly spaced over 360 degrees
  double range_m = 8.0;         // maximum range; beyond it a beam returns nothing
  double range_noise_m = 0.01;  // standard deviation of Gaussian noise on each returned range
};

// How far the SLAM pose estimate strays from the true pose. The map is drawn at the estimate.
struct PoseNoiseOptions {
  // Per scan, independent (scan-matching jitter): standard deviations.
  double xy_m = 0.01;
  double yaw_deg = 0.1;
  // Slow drift: a random walk of the estimate's error along the path, standard deviation after
  // 1 m of path (it grows as the square root of the distance travelled). 0 = no drift.
  double drift_xy_m = 0.0;
  double drift_yaw_deg = 0.0;
};

struct SimulationOptions {
  int robots = 4;  // robots in the building (a foreign robot comes on top)
  std::uint32_t seed = 1;
  LidarOptions lidar;
  PoseNoiseOptions pose_noise;
  double path_length_m = 50.0;       // exploration budget of each robot
  double scan_spacing_m = 0.2;       // a scan every this much path
  double clearance_m = 0.25;         // robot radius: paths keep this far from anything not free
  double goal_spread_m = 4.0;        // goals are drawn among unseen places up to this much further
                                     // than the nearest one (frontier-like exploration)
  double max_frame_offset_m = 20.0;  // |translation| of each map frame, per axis
  // Cell size of each robot's map: one value for all, or one per robot (foreign one last).
  std::vector<double> resolutions_m = {0.05};
  // Robots start far apart (farthest-point sampling) and each explores only the part of the
  // building closer to its start than to any other start: pairs share little more than the
  // boundaries they see across.
  bool little_overlap = false;
  // A cell is occupied in a robot's map when at least this share of the beams that reached it
  // ended in it (GMapping's occupancy threshold); reached by none: unknown.
  double occupied_ratio = 0.25;
  // The building's own map joins the case as a fixed base map (io/simulated_case.hpp), as in a
  // site job; a synthetic office's as it was generated.
  bool fixed_base = false;
  // Each robot of the building gets a known start pose (job.yaml's `initial_pose`, in the
  // building's frame) off its true frame pose by exactly these errors, as an operator's dock
  // poses are: the translation in a random direction, the yaw with a random sign (both from
  // `seed`), with these sigmas (`initial_pose_sigma`). nullopt: no priors. The foreign robot gets
  // none (its building is not the site).
  struct Priors {
    double error_m = 0.3;
    double error_deg = 5.0;
    double sigma_m = kDefaultPriorTranslationSigmaM;
    double sigma_deg = kDefaultPriorYawSigmaRad * 180.0 / M_PI;
  };
  std::optional<Priors> priors;
  int threads = 0;  // robots simulated in parallel (0: all cores); the result does not depend on it
};

// Throws fleetmerge::Error naming the option and the accepted range for the first bad value.
void ValidateSimulationOptions(const SimulationOptions& options);

}  // namespace fleetmerge
