// A simulated case on disk (io/simulated_case_file.hpp): the maps load back cell for cell,
// job.yaml loads as a job over them, truth.yaml holds the poses and overlaps exactly, and the
// building's own map is never overwritten.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <fstream>

#include "core/error.hpp"
#include "io/job_file.hpp"
#include "io/map_io.hpp"
#include "io/simulated_case_file.hpp"
#include "io/truth_file.hpp"
#include "sim/simulation.hpp"
#include "tests/support/shared_data.hpp"

namespace fleetmerge {
namespace {

namespace fs = std::filesystem;

SimulatedCase SmallCase() {
  SimulationOptions o;
  o.robots = 3;
  o.path_length_m = 20.0;
  o.resolutions_m = {0.05, 0.1, 0.05, 0.05};
  return SimulateFleet(OfficeBuilding(5), o, OfficeBuilding(6, "foreign"));
}

TEST(WriteSimulatedCase, RoundTripsThroughJobFileTruthAndMaps) {
  const SimulatedCase c = SmallCase();
  const fs::path dir = testing::MakeTempDir("simulated_case") / "case";
  const WrittenCase written = WriteSimulatedCase(c, dir);
  ASSERT_EQ(written.map_yamls.size(), 4u);

  const std::vector<Job> jobs = LoadJobFile(written.job_yaml);
  ASSERT_EQ(jobs.size(), 1u);
  ASSERT_EQ(jobs[0].maps.size(), 4u);
  EXPECT_EQ(fs::weakly_canonical(jobs[0].output_dir), fs::weakly_canonical(dir / "merged"));
  for (std::size_t k = 0; k < 4; ++k) {
    EXPECT_EQ(jobs[0].maps[k].name, c.names[k]);
    const LoadedMap loaded = LoadMap(jobs[0].maps[k].path);
    EXPECT_EQ(cv::countNonZero(loaded.grid.cells() != c.maps[k].cells()), 0) << c.names[k];
    EXPECT_NEAR(loaded.metadata.resolution_m, c.truth.maps[k].resolution_m, 1e-12);
    EXPECT_NEAR((loaded.grid.geometry().T_map_grid().translation_m() -
                 c.maps[k].geometry().T_map_grid().translation_m())
                    .norm(),
                0.0, 1e-6);
  }

  const YAML::Node truth = YAML::LoadFile(written.truth_yaml.string());
  EXPECT_EQ(truth["format"].as<std::string>(), "fleetmerge-truth-1");
  EXPECT_EQ(truth["seed"].as<std::uint32_t>(), 1u);
  ASSERT_EQ(truth["buildings"].size(), 2u);
  EXPECT_EQ(truth["buildings"][1]["name"].as<std::string>(), "foreign");
  ASSERT_EQ(truth["maps"].size(), 4u);
  for (std::size_t k = 0; k < 4; ++k) {
    const YAML::Node m = truth["maps"][k];
    EXPECT_EQ(m["name"].as<std::string>(), c.names[k]);
    EXPECT_TRUE(fs::exists(dir / m["file"].as<std::string>()));
    EXPECT_EQ(m["building"].as<std::string>(), k < 3 ? "office" : "foreign");
    EXPECT_EQ(m["resolution"].as<double>(), c.truth.maps[k].resolution_m);
    const Pose2& T = c.truth.maps[k].T_building_map;
    EXPECT_EQ(m["pose"]["x"].as<double>(), T.x_m()) << "poses are written exactly";
    EXPECT_EQ(m["pose"]["y"].as<double>(), T.y_m());
    EXPECT_EQ(m["pose"]["yaw"].as<double>(), T.yaw_rad());
  }
  ASSERT_EQ(truth["overlaps"].size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(truth["overlaps"][k]["cells"].as<long long>(), c.truth.overlaps[k].cells);
  }
}

// A case with a fixed base (`simulate --fixed-base`): the building's own map is written as
// base.yaml, cell for cell, and comes first in job.yaml (fixed at the identity) and in
// truth.yaml (at the identity, with its overlaps first); the robots follow as without a base.
TEST(WriteSimulatedCase, AFixedBaseComesFirstInTheJobAndTheTruth) {
  SimulationOptions o;
  o.robots = 3;
  o.path_length_m = 20.0;
  o.fixed_base = true;
  const SimulationBuilding office = OfficeBuilding(5);
  const SimulatedCase c = SimulateFleet(office, o, OfficeBuilding(6, "foreign"));
  ASSERT_TRUE(c.base.has_value());
  const fs::path dir = testing::MakeTempDir("simulated_case_base") / "case";
  const WrittenCase written = WriteSimulatedCase(c, dir);
  EXPECT_EQ(written.base_yaml, dir / "base.yaml");

  const std::vector<Job> jobs = LoadJobFile(written.job_yaml);
  ASSERT_EQ(jobs.size(), 1u);
  ASSERT_EQ(jobs[0].maps.size(), 5u);
  const JobMap& base = jobs[0].maps[0];
  EXPECT_EQ(base.name, "base");
  EXPECT_TRUE(base.fixed);
  EXPECT_EQ(base.T_merged_map.translation_m().norm(), 0.0);
  EXPECT_EQ(base.T_merged_map.yaw_rad(), 0.0);
  for (std::size_t k = 0; k < 4; ++k) {
    EXPECT_EQ(jobs[0].maps[k + 1].name, c.names[k]);
    EXPECT_FALSE(jobs[0].maps[k + 1].fixed) << c.names[k];
  }
  const LoadedMap loaded = LoadMap(base.path);
  EXPECT_EQ(cv::countNonZero(loaded.grid.cells() != office.grid.cells()), 0);
  EXPECT_NEAR((loaded.grid.geometry().T_map_grid().translation_m() -
               office.grid.geometry().T_map_grid().translation_m())
                  .norm(),
              0.0, 1e-6);

  const GroundTruth truth = LoadTruth(written.truth_yaml);
  ASSERT_EQ(truth.maps.size(), 5u);
  EXPECT_EQ(truth.maps[0].name, "base");
  EXPECT_EQ(truth.maps[0].file, dir / "base.yaml");
  EXPECT_EQ(truth.maps[0].building, "office");
  EXPECT_EQ(truth.maps[0].T_building_map.translation_m().norm(), 0.0);
  EXPECT_EQ(truth.maps[0].T_building_map.yaw_rad(), 0.0);
  for (std::size_t k = 0; k < 4; ++k) {
    EXPECT_EQ(truth.maps[k + 1].name, c.names[k]);
    EXPECT_EQ(truth.maps[k + 1].T_building_map.x_m(), c.truth.maps[k].T_building_map.x_m());
  }
  // The base overlaps the building's 3 robots, not the foreign one; then the robots' 3 pairs.
  ASSERT_EQ(truth.overlaps.size(), 6u);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(truth.overlaps[k].a, "base");
    EXPECT_EQ(truth.overlaps[k].b, c.names[k]);
    EXPECT_EQ(truth.overlaps[k].cells, c.base->overlaps[k].cells);
    EXPECT_EQ(truth.overlaps[k + 3].cells, c.truth.overlaps[k].cells);
  }
}

TEST(WriteSimulatedCase, NeverOverwritesAnInput) {
  const SimulatedCase c = SmallCase();
  const fs::path dir = testing::MakeTempDir("simulated_case_input");
  const fs::path building = dir / "robot2.yaml";
  std::ofstream(building) << "image: building.pgm\n";
  EXPECT_THROW(WriteSimulatedCase(c, dir, {building}), Error);
  EXPECT_FALSE(fs::exists(dir / "robot1.yaml")) << "checked before anything is written";
  EXPECT_FALSE(fs::exists(dir / "job.yaml"));
}

// The priors reach job.yaml as each robot's initial_pose and initial_pose_sigma, to the last bit;
// the foreign robot's entry has none.
TEST(WriteSimulatedCase, PriorsAreTheRobotsInitialPosesInTheJob) {
  SimulationOptions o;
  o.robots = 3;
  o.path_length_m = 20.0;
  o.fixed_base = true;
  o.priors = SimulationOptions::Priors{0.3, 5.0, 0.5, 10.0};
  const SimulatedCase c = SimulateFleet(OfficeBuilding(5), o, OfficeBuilding(6, "foreign"));
  const fs::path dir = testing::MakeTempDir("simulated_case_priors") / "case";
  const WrittenCase written = WriteSimulatedCase(c, dir);
  const std::vector<Job> jobs = LoadJobFile(written.job_yaml);
  ASSERT_EQ(jobs.size(), 1u);
  ASSERT_EQ(jobs[0].maps.size(), 5u);
  EXPECT_FALSE(jobs[0].maps[0].prior.has_value()) << "the base is fixed, not a prior";
  for (std::size_t k = 0; k < 3; ++k) {
    const JobMap& map = jobs[0].maps[k + 1];
    ASSERT_TRUE(map.prior.has_value()) << map.name;
    EXPECT_EQ(map.prior->T_site_map.x_m(), c.priors[k]->T_site_map.x_m());
    EXPECT_EQ(map.prior->T_site_map.y_m(), c.priors[k]->T_site_map.y_m());
    EXPECT_EQ(map.prior->T_site_map.yaw_rad(), c.priors[k]->T_site_map.yaw_rad());
    EXPECT_EQ(map.prior->translation_sigma_m, 0.5);
    EXPECT_EQ(map.prior->yaw_sigma_rad, c.priors[k]->yaw_sigma_rad);
  }
  EXPECT_FALSE(jobs[0].maps[4].prior.has_value()) << jobs[0].maps[4].name;
}

}  // namespace
}  // namespace fleetmerge
