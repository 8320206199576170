// Fuzzes the bag readers: every input is written as robot.bag (rosbag/ros1_bag), robot.mcap
// (rosbag/mcap_file) and robot.db3 (rosbag/sqlite_bag) and each is loaded as `merge --out` loads a
// bag (every map topic, io/map_inputs.hpp); the input is also decoded as one ROS 1 and one CDR
// nav_msgs/OccupancyGrid message (rosbag/occupancy_grid_msg). A loaded map must have the size its
// message announced. Anything but a clean load or a fleetmerge::Error (a crash, a sanitizer
// report, another exception, a hang) is a finding.
#include <cstdlib>
#include <string_view>

#include "core/error.hpp"
#include "io/map_inputs.hpp"
#include "rosbag/occupancy_grid_msg.hpp"
#include "tests/fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace fleetmerge;
  const std::filesystem::path dir = fuzz::ScratchDir();
  const char* bytes = reinterpret_cast<const char*>(data);
  constexpr std::int64_t kMaxCells = 1'000'000;  // keeps each input fast
  for (const char* name : {"robot.bag", "robot.mcap", "robot.db3"}) {
    const std::filesystem::path path = dir / name;
    fuzz::WriteBytes(path, bytes, size);
    try {
      for (const JobMap& map : ExpandMapInputs({{path, path, "", {}}})) {
        const LoadedMap loaded = LoadJobMap(map, kMaxCells);
        if (!loaded.bag || loaded.grid.width() <= 0 || loaded.grid.height() <= 0) abort();
      }
    } catch (const Error&) {
    }
  }
  const std::string_view message(bytes, size);
  for (bool cdr : {false, true}) {
    try {
      const OccupancyGridMsg msg =
          cdr ? DecodeCdrOccupancyGrid(message, "fuzz") : DecodeRos1OccupancyGrid(message, "fuzz");
      const OccupancyGrid grid = OccupancyGridFromMsg(msg, "fuzz", kMaxCells);
      if (static_cast<std::uint32_t>(grid.width()) != msg.width ||
          static_cast<std::uint32_t>(grid.height()) != msg.height) {
        abort();
      }
    } catch (const Error&) {
    }
  }
  return 0;
}
