#include "cli/example_command.hpp"

#include <cmath>
#include <ostream>
#include <random>
#include <sstream>

#include "cli/octree_example.hpp"
#include "io/atomic_file.hpp"
#include "io/map_io.hpp"
#include "sim/ground_truth_pair.hpp"
#include "sim/synthetic_office.hpp"

namespace fleetmerge {

int RunExampleCommand(const ExampleCommand& command, std::ostream& out) {
  if (command.octree) return RunOctreeExample(command, out);
  const OccupancyGrid building = GenerateOfficeFloor(OfficeOptions{}, command.seed);
  std::mt19937 rng(command.seed);
  const double yaw_rad = std::uniform_real_distribution<double>(-M_PI, M_PI)(rng);
  const GroundTruthPair pair = CutPair(building, yaw_rad, rng);

  std::filesystem::create_directories(command.out_dir);
  const auto a_yaml = command.out_dir / "robot_a.yaml";
  const auto b_yaml = command.out_dir / "robot_b.yaml";
  SaveMap(pair.a, a_yaml);
  SaveMap(pair.b, b_yaml);
  std::ostringstream truth;
  truth.precision(17);
  truth << "# True pose of robot_b's map frame in robot_a's map frame (metres, radians).\n"
        << "a: robot_a.yaml\nb: robot_b.yaml\n"
        << "T_a_b: {x: " << pair.T_a_b.x_m() << ", y: " << pair.T_a_b.y_m()
        << ", yaw: " << pair.T_a_b.yaw_rad() << "}\n";
  WriteFileAtomically(command.out_dir / "truth.yaml", truth.str());

  out << "wrote " << a_yaml.string() << ", " << b_yaml.string() << " and "
      << (command.out_dir / "truth.yaml").string() << "\n"
      << "true pose of b in a: x " << pair.T_a_b.x_m() << " m, y " << pair.T_a_b.y_m() << " m, yaw "
      << pair.T_a_b.yaw_rad() << " rad (" << pair.T_a_b.yaw_rad() * 180.0 / M_PI << " deg)\n";
  return 0;
}

}  // namespace fleetmerge
