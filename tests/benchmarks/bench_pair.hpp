// The benchmarks' 530 x 530 cell pair (the paper's size, Section IV-B): windows of the Intel lab
// map in ../shared (or of a synthetic office without it); b is rotated by 37 degrees and shifted
// by (10, 7.5) m. Used in process (pair_benchmark) and as map files (process_benchmark).
#pragma once

#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>

#include "core/occupancy_grid.hpp"
#include "io/map_io.hpp"
#include "pipeline/composite.hpp"
#include "sim/synthetic_office.hpp"
#include "tests/support/shared_data.hpp"

namespace fleetmerge {

constexpr int kBenchPairSide = 530;

struct BenchPair {
  OccupancyGrid a, b;
};

inline BenchPair MakeBenchPair() {
  OccupancyGrid building;
  if (const auto dir = testing::SharedMapsDir()) {
    building = LoadMap(*dir / "intel_lab.yaml").grid;
  } else {
    std::fprintf(stderr, "shared maps absent: benchmarking a synthetic office instead\n");
    OfficeOptions office;
    office.width_m = office.height_m = 40.0;
    building = GenerateOfficeFloor(office, 1);
  }
  const double r = building.geometry().resolution_m();
  const cv::Rect box = cv::boundingRect(building.cells() != 0);
  const Eigen::Vector2d corner =
      building.geometry().T_map_grid() * Eigen::Vector2d(box.x * r, box.y * r);
  const GridGeometry window(r, {kBenchPairSide, kBenchPairSide});
  const Pose2 T_building_a(corner, 0.0);
  const Pose2 T_building_b = T_building_a * Pose2(10.0, 7.5, 37.0 * M_PI / 180.0);
  BenchPair p;
  p.a = SampleOnto({&building, T_building_a.inverse()}, window);
  p.b = SampleOnto({&building, T_building_b.inverse()}, window);
  return p;
}

}  // namespace fleetmerge
