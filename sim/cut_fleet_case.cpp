#include "sim/cut_fleet_case.hpp"

#include <algorithm>
#include <random>

#include "io/atomic_file.hpp"
#include "io/map_io.hpp"

namespace fleetmerge {

std::vector<TruthOverlap> TrueOverlaps(const OccupancyGrid& building,
                                       const std::vector<OccupancyGrid>& maps,
                                       const std::vector<std::string>& names,
                                       const std::vector<Pose2>& T_building_map) {
  // known(k): which building cells map k observed, found by looking each building cell's centre
  // up in map k's grid.
  const GridGeometry& g = building.geometry();
  const std::size_t n = maps.size();
  std::vector<cv::Mat1b> known(n);
  std::vector<long long> known_cells(n, 0);
  for (std::size_t k = 0; k < n; ++k) {
    known[k] = cv::Mat1b::zeros(g.height(), g.width());
    const Pose2 T_map_building = T_building_map[k].inverse();
    for (int j = 0; j < g.height(); ++j) {
      for (int i = 0; i < g.width(); ++i) {
        const Eigen::Vector2d p_map = T_map_building * g.CellCenter({i, j});
        const bool seen =
            maps[k].StateOrUnknown(maps[k].geometry().CellOf(p_map)) != CellState::kUnknown;
        known[k](j, i) = seen;
        known_cells[k] += seen;
      }
    }
  }
  std::vector<TruthOverlap> overlaps;
  for (std::size_t a = 0; a < n; ++a) {
    for (std::size_t b = a + 1; b < n; ++b) {
      const long long cells = cv::countNonZero(known[a] & known[b]);
      if (cells == 0) continue;
      const long long smaller = std::min(known_cells[a], known_cells[b]);
      overlaps.push_back({names[a], names[b], cells, double(cells) / double(smaller)});
    }
  }
  return overlaps;
}

GroundTruth WriteCutFleetCase(const OccupancyGrid& building, const std::string& building_name,
                              const std::string& source, int robots, std::uint32_t seed,
                              const std::filesystem::path& dir, const CutFleetOptions& options,
                              const std::vector<std::filesystem::path>& protected_inputs) {
  for (int k = 0; k < robots; ++k) {
    const std::string name = "robot" + std::to_string(k + 1);
    CheckNotAnInput(dir / (name + ".yaml"), protected_inputs);
    CheckNotAnInput(dir / (name + ".pgm"), protected_inputs);
  }
  CheckNotAnInput(dir / "truth.yaml", protected_inputs);
  CheckNotAnInput(dir / "job.yaml", protected_inputs);
  std::mt19937 rng(seed);
  const GroundTruthFleet fleet = CutFleet(building, robots, rng, options);
  std::filesystem::create_directories(dir);
  GroundTruth truth;
  truth.seed = seed;
  truth.buildings.push_back({building_name, source});
  std::vector<std::string> names;
  std::string job = "# fleetmerge: a cut-fleet case of " + source + " (seed " +
                    std::to_string(seed) + ")\nmaps:\n";
  for (int k = 0; k < robots; ++k) {
    const std::string name = "robot" + std::to_string(k + 1);
    SaveMap(fleet.maps[k], dir / (name + ".yaml"), protected_inputs);
    names.push_back(name);
    truth.maps.push_back({name, name + ".yaml", building_name,
                          fleet.maps[k].geometry().resolution_m(), fleet.T_building_map[k]});
    job += "  - " + name + ".yaml\n";
  }
  job += "output: merged\n";
  truth.overlaps = TrueOverlaps(building, fleet.maps, names, fleet.T_building_map);
  SaveTruth(truth, dir / "truth.yaml");
  WriteFileAtomically(dir / "job.yaml", job, protected_inputs);
  for (TruthMap& map : truth.maps) map.file = dir / map.file;
  return truth;
}

}  // namespace fleetmerge
