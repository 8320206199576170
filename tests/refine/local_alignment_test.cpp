// The wall alignment's stopping rule (refine/local_alignment.hpp, function_tolerance), on the
// maps of robots simulated in MIT CSAIL (each map its own run, so two maps' walls disagree a
// little, as real maps do): started off the true pose, a tighter tolerance follows the same
// Levenberg-Marquardt steps further, so it never ends at a higher cost, and the final stage's
// 1e-7 (PairOptions::final_refine) ends nearer the minimum than Ceres' default 1e-6.
#include "refine/local_alignment.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "core/hypothesis_generator.hpp"
#include "io/map_io.hpp"
#include "job/pair_options.hpp"
#include "sim/simulation.hpp"
#include "tests/support/shared_data.hpp"
#include "tests/support/simulated_pairs.hpp"

namespace fleetmerge {
namespace {

// Distance of two cell-unit poses: translation in cells plus the yaw's arc at 50 cells.
double PoseDistanceCells(const Pose2& p, const Pose2& q) {
  return std::hypot(p.x_m() - q.x_m(), p.y_m() - q.y_m()) +
         50.0 * std::abs(WrapAngle(p.yaw_rad() - q.yaw_rad()));
}

TEST(LocalAlignment, TighterToleranceEndsNearerTheMinimum) {
  FLEETMERGE_REQUIRE_SHARED_MAPS();
  const auto path = *testing::SharedMapsDir() / "mit_csail.yaml";
  SimulationOptions simulation;
  simulation.robots = 5;
  simulation.seed = 65;
  simulation.path_length_m = 100.0;
  const SimulatedCase sim = SimulateFleet({LoadMap(path).grid, "csail", path.string()}, simulation);
  const PairOptions pair_options;
  const LocalAlignmentOptions tight = pair_options.final_refine;
  ASSERT_EQ(tight.function_tolerance, 1e-7);
  LocalAlignmentOptions loose = tight, exhaustive = tight;  // the same iteration bound
  loose.function_tolerance = 1e-6;
  exhaustive.function_tolerance = 1e-14;

  std::mt19937 rng(3);
  std::uniform_real_distribution<double> offset(-1.5, 1.5), turn(-0.02, 0.02);
  double loose_sum = 0.0, tight_sum = 0.0;
  int pairs = 0;
  for (const testing::TruePair& pair : testing::TruePairs(sim, 5000)) {
    const OccupancyGrid& map_a = sim.maps[pair.a];
    const OccupancyGrid& map_b = sim.maps[pair.b];
    const Pose2 start = CellPoseFromMapPose(map_a.geometry(), map_b.geometry(), pair.T_a_b) *
                        Pose2(offset(rng), offset(rng), turn(rng));
    const AlignmentTarget a(map_a, pair_options.refine_truncation_cells);
    const AlignmentTarget b(map_b, pair_options.refine_truncation_cells);
    const LocalAlignmentResult r_loose = RefineAlignment(a, b, start, loose);
    const LocalAlignmentResult r_tight = RefineAlignment(a, b, start, tight);
    const LocalAlignmentResult r_best = RefineAlignment(a, b, start, exhaustive);
    const std::string name = sim.names[pair.a] + "-" + sim.names[pair.b];
    ASSERT_TRUE(r_loose.converged && r_tight.converged && r_best.converged) << name;
    // The same steps, continued: never a higher cost.
    EXPECT_LE(r_tight.cost, r_loose.cost) << name;
    EXPECT_LE(r_best.cost, r_tight.cost) << name;
    const double loose_cells = PoseDistanceCells(r_loose.T_ga_gb, r_best.T_ga_gb);
    const double tight_cells = PoseDistanceCells(r_tight.T_ga_gb, r_best.T_ga_gb);
    std::printf("[ %s ] from the minimum: 1e-6 %.4f cells, 1e-7 %.4f cells\n", name.c_str(),
                loose_cells, tight_cells);
    loose_sum += loose_cells;
    tight_sum += tight_cells;
    ++pairs;
  }
  ASSERT_GE(pairs, 5);
  std::printf("[ mean ] 1e-6 %.4f cells, 1e-7 %.4f cells over %d pairs\n", loose_sum / pairs,
              tight_sum / pairs, pairs);
  EXPECT_LT(tight_sum, 0.5 * loose_sum);
}

}  // namespace
}  // namespace fleetmerge
