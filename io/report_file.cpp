#include "io/report_file.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/error.hpp"

namespace fleetmerge {
namespace {

using nlohmann::json;

// Errors name the file and the field path ("maps[2].pose.yaw").
class ReportErrors {
 public:
  explicit ReportErrors(const std::filesystem::path& path) : path_(path.string()) {}
  [[noreturn]] void Fail(const std::string& field, const std::string& what) const {
    throw Error(path_ + ": field '" + field + "': " + what);
  }
  [[noreturn]] void Expected(const std::string& field, const std::string& expected,
                             const json& got) const {
    std::string text = got.dump();
    if (text.size() > 60) text = text.substr(0, 57) + "...";
    Fail(field, "expected " + expected + ", got " + text);
  }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

const json& Member(const json& object, const std::string& field, const std::string& key,
                   const ReportErrors& errors) {
  const auto it = object.find(key);
  if (it == object.end()) errors.Fail(field + "." + key, "missing");
  return *it;
}

const json& Array(const json& object, const std::string& key, const ReportErrors& errors) {
  const auto it = object.find(key);
  if (it == object.end()) errors.Fail(key, "missing: expected a list");
  if (!it->is_array()) errors.Expected(key, "a list", *it);
  return *it;
}

std::string ReadName(const json& value, const std::string& field, const ReportErrors& errors) {
  if (!value.is_string() || value.get<std::string>().empty()) {
    errors.Expected(field, "a non-empty string", value);
  }
  return value.get<std::string>();
}

int ReadIndex(const json& value, const std::string& field, const ReportErrors& errors) {
  if (!value.is_number_integer() || value.get<long long>() < 0 ||
      value.get<long long>() > 1000000000) {
    errors.Expected(field, "an integer >= 0", value);
  }
  return value.get<int>();
}

double ReadFinite(const json& value, const std::string& field, const ReportErrors& errors) {
  if (!value.is_number() || !std::isfinite(value.get<double>())) {
    errors.Expected(field, "a finite number", value);
  }
  return value.get<double>();
}

ReportMap ReadMap(const json& value, const std::string& field, const ReportErrors& errors) {
  if (!value.is_object()) errors.Expected(field, "an object {name, component, pose}", value);
  ReportMap map;
  map.name = ReadName(Member(value, field, "name", errors), field + ".name", errors);
  map.component =
      ReadIndex(Member(value, field, "component", errors), field + ".component", errors);
  const json& pose = Member(value, field, "pose", errors);
  const std::string pose_field = field + ".pose";
  if (!pose.is_object()) errors.Expected(pose_field, "an object {x, y, yaw}", pose);
  map.T_component_map =
      Pose2(ReadFinite(Member(pose, pose_field, "x", errors), pose_field + ".x", errors),
            ReadFinite(Member(pose, pose_field, "y", errors), pose_field + ".y", errors),
            ReadFinite(Member(pose, pose_field, "yaw", errors), pose_field + ".yaw", errors));
  return map;
}

ReportComponent ReadComponent(const json& value, const std::string& field,
                              const ReportErrors& errors) {
  if (!value.is_object()) errors.Expected(field, "an object {id, maps}", value);
  ReportComponent component;
  component.id = ReadIndex(Member(value, field, "id", errors), field + ".id", errors);
  const json& maps = Member(value, field, "maps", errors);
  if (!maps.is_array() || maps.empty()) {
    errors.Expected(field + ".maps", "a non-empty list of map names", maps);
  }
  for (std::size_t i = 0; i < maps.size(); ++i) {
    component.maps.push_back(ReadName(maps[i], field + ".maps[" + std::to_string(i) + "]", errors));
  }
  return component;
}

json ParseFile(const std::filesystem::path& path, const ReportErrors& errors) {
  std::ifstream in(path, std::ios::binary);
  if (!in || std::filesystem::is_directory(path)) {
    throw Error(path.string() +
                ": cannot open report (expected the report.json of "
                "`fleetmerge merge`)");
  }
  std::ostringstream text;
  text << in.rdbuf();
  try {
    return json::parse(text.str());
  } catch (const json::parse_error& e) {
    throw Error(errors.path() + ": malformed JSON: " + e.what());
  }
}

}  // namespace

MergeReport LoadMergeReport(const std::filesystem::path& path) {
  const ReportErrors errors(path);
  const json root = ParseFile(path, errors);
  if (!root.is_object()) {
    throw Error(path.string() + ": expected a report object with 'maps' and 'components'");
  }
  MergeReport report;
  const json& maps = Array(root, "maps", errors);
  std::map<std::string, int> index;
  for (std::size_t i = 0; i < maps.size(); ++i) {
    const std::string field = "maps[" + std::to_string(i) + "]";
    report.maps.push_back(ReadMap(maps[i], field, errors));
    if (!index.emplace(report.maps.back().name, static_cast<int>(i)).second) {
      errors.Fail(field + ".name", "map name '" + report.maps.back().name + "' appears twice");
    }
  }
  const json& components = Array(root, "components", errors);
  for (std::size_t c = 0; c < components.size(); ++c) {
    const std::string field = "components[" + std::to_string(c) + "]";
    report.components.push_back(ReadComponent(components[c], field, errors));
    const ReportComponent& component = report.components.back();
    if (component.id != static_cast<int>(c)) {
      errors.Fail(field + ".id", "expected " + std::to_string(c) + " (its index), got " +
                                     std::to_string(component.id));
    }
    for (std::size_t k = 0; k < component.maps.size(); ++k) {
      const auto it = index.find(component.maps[k]);
      const std::string map_field = field + ".maps[" + std::to_string(k) + "]";
      if (it == index.end()) {
        errors.Fail(map_field, "'" + component.maps[k] + "' is not one of the report's maps");
      }
      if (report.maps[it->second].component != static_cast<int>(c)) {
        errors.Fail(map_field, "'" + component.maps[k] + "' has component " +
                                   std::to_string(report.maps[it->second].component) +
                                   " in 'maps'");
      }
    }
  }
  for (std::size_t i = 0; i < report.maps.size(); ++i) {
    const ReportMap& map = report.maps[i];
    const bool listed = map.component < static_cast<int>(report.components.size()) &&
                        std::count(report.components[map.component].maps.begin(),
                                   report.components[map.component].maps.end(), map.name) == 1;
    if (!listed) {
      errors.Fail("maps[" + std::to_string(i) + "].component",
                  "map '" + map.name + "' is not listed (once) in components[" +
                      std::to_string(map.component) + "]");
    }
  }
  return report;
}

}  // namespace fleetmerge
