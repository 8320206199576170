// Reading back the report.json that `fleetmerge merge` writes (pipeline/report_json.hpp): each
// map's component and pose, and the components. Only the fields a tool needs to judge the result
// (`fleetmerge eval`) are read; other fields are ignored, so fields may be added to the report.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "core/pose2.hpp"

namespace fleetmerge {

struct ReportMap {
  std::string name;
  int component = -1;     // index into MergeReport::components
  Pose2 T_component_map;  // the map's frame in its component's merged frame
};

struct ReportComponent {
  int id = 0;                     // == its index
  std::vector<std::string> maps;  // names, each a ReportMap's
};

struct MergeReport {
  std::vector<ReportMap> maps;
  std::vector<ReportComponent> components;
};

// Reads and checks `path`: JSON syntax, the types of maps[].{name, component, pose{x, y, yaw}}
// and components[].{id, maps}, finite poses, unique map names, components that exist and agree
// with the maps' `component`. Throws fleetmerge::Error "<path>: field 'maps[2].pose.yaw':
// expected a finite number, got "abc"".
MergeReport LoadMergeReport(const std::filesystem::path& path);

}  // namespace fleetmerge
