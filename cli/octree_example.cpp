#include "cli/octree_example.hpp"

#include <cmath>
#include <ostream>
#include <random>
#include <sstream>

#include "io/atomic_file.hpp"
#include "io/octree_io.hpp"
#include "octree/synthetic_octree.hpp"
#include "sim/ground_truth_pair.hpp"
#include "sim/synthetic_office.hpp"

namespace fleetmerge {

int RunOctreeExample(const ExampleCommand& command, std::ostream& out) {
  OfficeOptions office;
  office.resolution_m = 0.1;  // 10 cm voxels: a 30 x 20 m storey in about a second
  office.wall_thickness_m = 0.2;
  const OccupancyGrid building = GenerateOfficeFloor(office, command.seed);
  std::mt19937 rng(command.seed);
  const double yaw_rad = std::uniform_real_distribution<double>(-M_PI, M_PI)(rng);
  const GroundTruthPair pair = CutPair(building, yaw_rad, rng);
  // Each robot's frame at its own height above the building's floor (z = 0).
  std::uniform_real_distribution<double> height(-1.0, 1.0);
  const double z_a_m = height(rng), z_b_m = height(rng);

  std::filesystem::create_directories(command.out_dir);
  ExtrudeOptions a, b;
  a.floor_z_m = -z_a_m;
  b.floor_z_m = -z_b_m;
  SaveOctree(*ExtrudeFloorPlan(pair.a, a), command.out_dir / "robot_a.bt");
  SaveOctree(*ExtrudeFloorPlan(pair.b, b), command.out_dir / "robot_b.bt");
  std::ostringstream truth;
  truth.precision(17);
  truth << "# True pose of robot_b's octree frame in robot_a's (metres, radians).\n"
        << "a: robot_a.bt\nb: robot_b.bt\n"
        << "T_a_b: {x: " << pair.T_a_b.x_m() << ", y: " << pair.T_a_b.y_m()
        << ", yaw: " << pair.T_a_b.yaw_rad() << ", z: " << z_b_m - z_a_m << "}\n";
  WriteFileAtomically(command.out_dir / "truth.yaml", truth.str());
  WriteFileAtomically(command.out_dir / "job.yaml",
                      "# fleetmerge merge job.yaml: two octrees of one storey\n"
                      "maps: [robot_a.bt, robot_b.bt]\noutput: merged\n");

  out << "wrote robot_a.bt, robot_b.bt, truth.yaml and job.yaml in " << command.out_dir.string()
      << "\ntrue pose of b in a: x " << pair.T_a_b.x_m() << " m, y " << pair.T_a_b.y_m()
      << " m, yaw " << pair.T_a_b.yaw_rad() << " rad, z " << z_b_m - z_a_m << " m\n"
      << "merge them: fleetmerge merge " << (command.out_dir / "job.yaml").string() << "\n";
  return 0;
}

}  // namespace fleetmerge
