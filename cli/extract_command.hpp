// `fleetmerge extract BAG... --out DIR`: each map topic's last map as map_server YAML + PGM (as
// map_saver writes them), named as merge would name them, so a user can inspect and reuse them.
#pragma once

#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

namespace fleetmerge {

struct ExtractCommand {
  std::vector<std::filesystem::path> bags;
  std::filesystem::path out_dir;
  std::vector<std::string> topics;  // empty: every nav_msgs/OccupancyGrid topic
};

// Every map is read before any file is written: a bad bag leaves the folder untouched.
int RunExtractCommand(const ExtractCommand& command, std::ostream& out);

}  // namespace fleetmerge
