// Fleet merging on real maps cut into seeded robot maps with known frames
// (sim/ground_truth_pair.hpp, CutFleet).
#include "pipeline/fleet_merge.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <opencv2/imgproc.hpp>
#include <random>

#include "core/acceptance_index.hpp"
#include "core/hypothesis_generator.hpp"
#include "core/resample.hpp"
#include "io/map_io.hpp"
#include "pipeline/composite.hpp"
#include "pipeline/preview.hpp"
#include "sim/ground_truth_pair.hpp"
#include "tests/support/shared_data.hpp"

namespace fleetmerge {
namespace {

OccupancyGrid LoadShared(const char* name) {
  return LoadMap(*testing::SharedMapsDir() / name).grid;
}

std::vector<const OccupancyGrid*> Pointers(const std::vector<OccupancyGrid>& maps) {
  std::vector<const OccupancyGrid*> out;
  for (const auto& m : maps) out.push_back(&m);
  return out;
}

// Cells known in both maps under their true relative pose.
std::int64_t TrueOverlap(const GroundTruthFleet& f, int a, int b) {
  const Pose2 T_a_b = f.T_building_map[a].inverse() * f.T_building_map[b];
  const Agreement g = CountAgreement(
      f.maps[a], f.maps[b], CellPoseFromMapPose(f.maps[a].geometry(), f.maps[b].geometry(), T_a_b));
  return g.agree + g.disagree;
}

// Every pair of maps merged together: relative pose within 1 degree and 3 cells (mean
// displacement of b's walls), compared with the truth.
void ExpectRelativePosesAccurate(const GroundTruthFleet& truth, const FleetResult& result,
                                 int first, int count) {
  for (int a = first; a < first + count; ++a) {
    for (int b = a + 1; b < first + count; ++b) {
      ASSERT_EQ(result.component_of[a], result.component_of[b]) << a << " and " << b;
      const Pose2 estimate = result.T_component_map[a].inverse() * result.T_component_map[b];
      const Pose2 T_true = truth.T_building_map[a].inverse() * truth.T_building_map[b];
      const PoseError e = ComparePoses(truth.maps[b], estimate, T_true);
      EXPECT_LE(e.yaw_deg, 1.0) << a << "-" << b;
      EXPECT_LE(e.mean_displacement_cells, 3.0) << a << "-" << b;
    }
  }
}

void PrintPairs(const char* label, const GroundTruthFleet& truth, const FleetResult& r) {
  for (const auto& p : r.pairs) {
    std::printf("[ pairs ] %s %d-%d omega %.3f walls %.3f overlap %lld (true overlap %lld) %s %s\n",
                label, p.a, p.b, p.best_omega(), p.wall_agreement,
                static_cast<long long>(p.overlap_cells),
                static_cast<long long>(
                    p.b < static_cast<int>(truth.maps.size()) ? TrueOverlap(truth, p.a, p.b) : -1),
                p.accepted ? "accepted" : "rejected", p.note.c_str());
  }
  std::printf("[ timing ] %s pairs %.0f ms, refine %.0f ms, composite %.0f ms\n", label,
              r.timing.pairs_ms, r.timing.refine_ms, r.timing.composite_ms);
}

struct FleetCase {
  const char* map;
  int robots;
};

class FleetAccuracy : public ::testing::TestWithParam<FleetCase> {};

TEST_P(FleetAccuracy, AllRelativePosesWithinOneDegreeAndThreeCells) {
  FLEETMERGE_REQUIRE_SHARED_MAPS();
  std::mt19937 rng(11);
  const GroundTruthFleet fleet = CutFleet(LoadShared(GetParam().map), GetParam().robots, rng);
  const FleetResult result = MergeFleet(Pointers(fleet.maps), 0, FleetOptions{});
  PrintPairs(GetParam().map, fleet, result);
  ASSERT_EQ(result.components.size(), 1u) << "every robot overlaps some other";
  ExpectRelativePosesAccurate(fleet, result, 0, GetParam().robots);
  EXPECT_TRUE(result.components[0].merged.has_value());
  EXPECT_TRUE(result.T_component_map[0].translation_m().isZero()) << "reference has identity";
}

INSTANTIATE_TEST_SUITE_P(RealMaps, FleetAccuracy,
                         ::testing::Values(FleetCase{"intel_lab.yaml", 4},
                                           FleetCase{"willow-full-0.05.yaml", 6},
                                           FleetCase{"aces3_austin.yaml", 4}),
                         [](const auto& info) {
                           return std::string(info.param.map).substr(0, 5) + "_" +
                                  std::to_string(info.param.robots);
                         });

TEST(FleetMerge, ForeignMapStaysUnmergedAndTwoBuildingsGiveTwoComponents) {
  FLEETMERGE_REQUIRE_SHARED_MAPS();
  std::mt19937 rng(5);
  const GroundTruthFleet intel = CutFleet(LoadShared("intel_lab.yaml"), 4, rng);
  const GroundTruthFleet csail = CutFleet(LoadShared("mit_csail.yaml"), 4, rng);
  std::vector<OccupancyGrid> maps = intel.maps;
  maps.push_back(csail.maps[0]);  // a robot that explored another building
  const FleetResult one_foreign = MergeFleet(Pointers(maps), 0, FleetOptions{});
  PrintPairs("intel+1 csail", intel, one_foreign);
  EXPECT_EQ(one_foreign.components.size(), 2u);
  const int foreign = one_foreign.component_of[4];
  EXPECT_NE(foreign, one_foreign.component_of[0]);
  EXPECT_EQ(one_foreign.components[foreign].maps.size(), 1u);
  EXPECT_FALSE(one_foreign.components[foreign].merged.has_value()) << "never forced in";
  ExpectRelativePosesAccurate(intel, one_foreign, 0, 4);

  maps.insert(maps.end(), csail.maps.begin() + 1, csail.maps.end());
  const FleetResult two = MergeFleet(Pointers(maps), 0, FleetOptions{});
  PrintPairs("intel+csail", intel, two);
  EXPECT_EQ(two.components.size(), 2u);
  for (int m = 0; m < 8; ++m) EXPECT_EQ(two.component_of[m], m < 4 ? 0 : 1) << m;
}

// Users navigate in the reference robot's map: the merged grid must hold its cells as they are,
// also when another map reaches lower than the reference (the merged grid's corner is then not
// the reference's) and when the reference is coarser than the other maps.
void ExpectReferenceCellForCell(const FleetResult& result, const std::vector<OccupancyGrid>& maps,
                                int reference) {
  const FleetComponent& component = result.components[result.component_of[reference]];
  ASSERT_EQ(component.reference, reference);
  ASSERT_TRUE(component.merged.has_value());
  const OccupancyGrid& merged = *component.merged;
  const OccupancyGrid& ref = maps[reference];
  EXPECT_DOUBLE_EQ(merged.geometry().resolution_m(), ref.geometry().resolution_m());
  // Not vacuous: some other map reaches below or left of the reference's known cells.
  const cv::Rect known = cv::boundingRect(ref.cells());
  const Eigen::Vector2d ref_corner_in_merged =
      merged.geometry().T_map_grid().inverse() * ref.geometry().T_map_grid() *
      Eigen::Vector2d(known.x, known.y) * ref.geometry().resolution_m();
  ASSERT_TRUE((ref_corner_in_merged.array() > 1.5 * ref.geometry().resolution_m()).any())
      << "the reference has the lowest corner: pick another";
  // The other maps' states on the merged cells, as compositing sees them (SampleOnto is tested
  // against a cell-by-cell lookup in composite_test).
  std::vector<OccupancyGrid> others;
  for (const int m : component.maps) {
    if (m == reference) continue;
    const OccupancyGrid at_merged = ResampleToResolution(maps[m], merged.geometry().resolution_m());
    others.push_back(SampleOnto({&at_merged, result.T_component_map[m]}, merged.geometry()));
  }
  std::int64_t only_reference = 0, checked = 0;
  for (int j = 0; j < ref.height(); ++j) {
    for (int i = 0; i < ref.width(); ++i) {
      if (ref.at({i, j}) == CellState::kUnknown) continue;
      const Eigen::Vector2d p = ref.geometry().CellCenter({i, j});  // merged frame = ref's frame
      const Eigen::Array2i cell = merged.geometry().CellOf(p);
      ASSERT_TRUE(merged.geometry().Contains(cell));
      // The same cell, not a neighbour half a cell off.
      ASSERT_LT((merged.geometry().CellCenter(cell) - p).norm(), 1e-6) << i << ", " << j;
      ++checked;
      bool others_unknown = true;
      for (const OccupancyGrid& sampled : others) {
        if (sampled.at(cell) != CellState::kUnknown) others_unknown = false;
      }
      if (!others_unknown) continue;
      ++only_reference;
      ASSERT_EQ(merged.at(cell), ref.at({i, j})) << "reference cell " << i << ", " << j;
    }
  }
  std::printf(
      "[ reference ] map %d: %lld known cells on the merged lattice, %lld known only to it "
      "and kept as they are\n",
      reference, static_cast<long long>(checked), static_cast<long long>(only_reference));
  EXPECT_GT(only_reference, checked / 10);
}

TEST(FleetMerge, ReferenceMapComesOutCellForCell) {
  FLEETMERGE_REQUIRE_SHARED_MAPS();
  std::mt19937 rng(11);
  GroundTruthFleet fleet = CutFleet(LoadShared("intel_lab.yaml"), 4, rng);
  for (const int reference : {1, 3}) {
    const FleetResult result = MergeFleet(Pointers(fleet.maps), reference, FleetOptions{});
    ASSERT_EQ(result.components.size(), 1u);
    ExpectReferenceCellForCell(result, fleet.maps, reference);
  }
  // A coarser reference: the merged map is at its resolution, on its cells.
  fleet.maps[3] =
      ResampleToResolution(fleet.maps[3], 2.0 * fleet.maps[3].geometry().resolution_m());
  const FleetResult coarse = MergeFleet(Pointers(fleet.maps), 3, FleetOptions{});
  ASSERT_EQ(coarse.components.size(), 1u);
  ExpectReferenceCellForCell(coarse, fleet.maps, 3);
}

TEST(FleetMerge, ResultDoesNotDependOnThreadCount) {
  FLEETMERGE_REQUIRE_SHARED_MAPS();
  std::mt19937 rng(8);
  const GroundTruthFleet fleet = CutFleet(LoadShared("intel_lab.yaml"), 4, rng);
  FleetOptions one, two;
  one.threads = 1;
  two.threads = 3;
  const FleetResult r1 = MergeFleet(Pointers(fleet.maps), 0, one);
  const FleetResult r2 = MergeFleet(Pointers(fleet.maps), 0, two);
  ASSERT_EQ(r1.pairs.size(), r2.pairs.size());
  for (std::size_t k = 0; k < r1.pairs.size(); ++k) {
    ASSERT_EQ(r1.pairs[k].hypotheses.size(), r2.pairs[k].hypotheses.size());
    for (std::size_t h = 0; h < r1.pairs[k].hypotheses.size(); ++h) {
      EXPECT_EQ(r1.pairs[k].hypotheses[h].omega, r2.pairs[k].hypotheses[h].omega);
      EXPECT_EQ(r1.pairs[k].hypotheses[h].T_a_b.x_m(), r2.pairs[k].hypotheses[h].T_a_b.x_m());
    }
  }
  for (int m = 0; m < 4; ++m) {
    EXPECT_EQ(r1.T_component_map[m].x_m(), r2.T_component_map[m].x_m());
    EXPECT_EQ(r1.T_component_map[m].yaw_rad(), r2.T_component_map[m].yaw_rad());
  }
}

// A job that writes asks for previews: made while compositing, they are ColourPreview's images;
// where the merged cells are not the compared ones the preview is left to the writer.
TEST(FleetMerge, PreviewsMadeWhileCompositingAreColourPreviews) {
  FLEETMERGE_REQUIRE_SHARED_MAPS();
  std::mt19937 rng(8);
  const GroundTruthFleet fleet = CutFleet(LoadShared("intel_lab.yaml"), 4, rng);
  FleetOptions options;
  EXPECT_TRUE(MergeFleet(Pointers(fleet.maps), 0, options).components.front().preview.empty());
  options.previews = true;
  const FleetResult result = MergeFleet(Pointers(fleet.maps), 0, options);
  ASSERT_EQ(result.components.size(), 1u);
  const FleetComponent& component = result.components.front();
  ASSERT_TRUE(component.merged);
  std::vector<CompositeInput> inputs;
  for (const int m : component.maps) {
    inputs.push_back({&result.maps[m], result.T_component_map[m]});
  }
  const cv::Mat3b expected = ColourPreview(inputs, *component.merged);
  ASSERT_EQ(component.preview.size(), expected.size());
  cv::Mat difference;
  cv::absdiff(component.preview, expected, difference);
  EXPECT_EQ(cv::countNonZero(difference.reshape(1)), 0);
  // A coarser reference: compared at the finest cells, merged on the reference's.
  std::vector<OccupancyGrid> maps = fleet.maps;
  maps[1] = ResampleToResolution(maps[1], 2.0 * maps[1].geometry().resolution_m());
  const FleetResult coarse = MergeFleet(Pointers(maps), 1, options);
  ASSERT_TRUE(coarse.components.front().merged);
  EXPECT_TRUE(coarse.components.front().preview.empty());
}

}  // namespace
}  // namespace fleetmerge
