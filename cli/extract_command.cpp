#include "cli/extract_command.hpp"

#include <iomanip>
#include <ostream>

#include "core/error.hpp"
#include "io/bag_maps.hpp"
#include "io/map_inputs.hpp"

namespace fleetmerge {

int RunExtractCommand(const ExtractCommand& command, std::ostream& out) {
  std::vector<MapInput> inputs;
  for (const auto& bag : command.bags) {
    if (!IsBagPath(bag)) {
      throw Error(bag.string() +
                  ": not a bag (expected a ROS 1 .bag, a ROS 2 bag folder, or a "
                  ".db3 or .mcap file)");
    }
    inputs.push_back({bag, bag, "", command.topics});
  }
  const std::vector<JobMap> maps = ExpandMapInputs(inputs);
  std::vector<LoadedMap> loaded;
  for (const JobMap& map : maps) loaded.push_back(LoadJobMap(map));
  std::vector<std::filesystem::path> protect;
  for (const JobMap& map : maps) protect.push_back(map.path);
  for (std::size_t m = 0; m < maps.size(); ++m) {
    const std::filesystem::path yaml = command.out_dir / (maps[m].name + ".yaml");
    std::filesystem::create_directories(yaml.parent_path());
    SaveMap(loaded[m].grid, yaml, protect);
    const BagMapInfo& bag = *loaded[m].bag;
    out << maps[m].source.string() << " topic " << bag.topic << " (" << loaded[m].grid.width()
        << " x " << loaded[m].grid.height() << " cells, "
        << loaded[m].grid.geometry().resolution_m() << " m, received " << std::fixed
        << std::setprecision(3) << bag.log_time_ns * 1e-9 << " s) -> " << yaml.string() << "\n";
    out.unsetf(std::ios::floatfield);
  }
  return 0;
}

}  // namespace fleetmerge
