// LoadTruth: truth.yaml against the fleetmerge-truth-1 schema (io/truth_file.hpp), every mistake
// reported in the house format of io/yaml_errors.hpp.
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <string>

#include "core/error.hpp"
#include "io/truth_file.hpp"
#include "io/yaml_errors.hpp"
#include "io/yaml_fields.hpp"

namespace fleetmerge {
namespace fs = std::filesystem;
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr const char* kFormat = "fleetmerge-truth-1";

// A list field, possibly empty.
void RequireList(const YamlField& field, const std::string& expected, const YamlErrors& errors) {
  if (!field.value.IsSequence()) FailExpected(field, expected, errors);
}

// Names seen so far in one list, with where (for "also the name of ...").
class NameIndex {
 public:
  explicit NameIndex(std::string what) : what_(std::move(what)) {}
  void Add(const std::string& name, const YamlField& field, const YamlErrors& errors) {
    const auto [it, inserted] = lines_.emplace(name, field.line);
    if (!inserted) {
      errors.Fail(field.key, field.line,
                  what_ + " name '" + name + "' appears twice (first at line " +
                      std::to_string(it->second) + ")");
    }
  }
  bool Has(const std::string& name) const { return lines_.count(name) > 0; }

 private:
  std::string what_;
  std::map<std::string, int> lines_;
};

TruthBuilding ReadBuilding(const YamlField& field, const YamlErrors& errors) {
  const YamlMapping building(field, {"name", "source"}, "a building {name, source}", errors);
  TruthBuilding b;
  b.name = ReadString(building.Require("name", "a building name"), "a building name", errors);
  b.source = ReadString(building.Require("source", "the building's map or a description"),
                        "the building's map or a description", errors);
  return b;
}

// An unquoted finite number (not NaN, not infinity).
double ReadFinite(const YamlField& field, const std::string& unit, const YamlErrors& errors) {
  double value = 0.0;
  if (!field.value.IsScalar() || field.value.Tag() == "!" ||
      !YAML::convert<double>::decode(field.value, value) || !std::isfinite(value)) {
    FailExpected(field, "a finite number (" + unit + ")", errors);
  }
  return value;
}

Pose2 ReadPose(const YamlField& field, const YamlErrors& errors) {
  const YamlMapping pose(field, {"x", "y", "yaw"}, "a pose {x, y, yaw} (m, m, rad)", errors);
  const double x = ReadFinite(pose.Require("x", "metres"), "metres", errors);
  const double y = ReadFinite(pose.Require("y", "metres"), "metres", errors);
  const double yaw = ReadFinite(pose.Require("yaw", "radians"), "radians", errors);
  return Pose2(x, y, yaw);
}

TruthMap ReadMap(const YamlField& field, const fs::path& folder, const NameIndex& buildings,
                 const YamlErrors& errors) {
  const YamlMapping map(field, {"name", "file", "building", "resolution", "pose"},
                        "a map {name, file, building, resolution, pose}", errors);
  TruthMap m;
  m.name = ReadString(map.Require("name", "a map name"), "a map name", errors);
  const fs::path file =
      ReadString(map.Require("file", "the map's YAML file"), "the map's YAML file", errors);
  m.file = file.is_absolute() ? file : folder / file;
  const YamlField building = map.Require("building", "the name of a listed building");
  m.building = ReadString(building, "the name of a listed building", errors);
  if (!buildings.Has(m.building)) {
    FailExpected(building, "the name of a building listed under 'buildings'", errors);
  }
  m.resolution_m = ReadNumber(map.Require("resolution", "metres per cell"), 0, kInf, true, errors);
  m.T_building_map = ReadPose(map.Require("pose", "a pose {x, y, yaw}"), errors);
  return m;
}

TruthOverlap ReadOverlap(const YamlField& field, const std::map<std::string, std::size_t>& maps,
                         const GroundTruth& truth, const YamlErrors& errors) {
  const YamlMapping overlap(field, {"a", "b", "cells", "share"}, "an overlap {a, b, cells, share}",
                            errors);
  TruthOverlap o;
  const YamlField a = overlap.Require("a", "a map name");
  const YamlField b = overlap.Require("b", "a map name");
  o.a = ReadString(a, "a map name", errors);
  o.b = ReadString(b, "a map name", errors);
  const auto ia = maps.find(o.a), ib = maps.find(o.b);
  if (ia == maps.end()) FailExpected(a, "the name of a map listed under 'maps'", errors);
  if (ib == maps.end()) FailExpected(b, "the name of a map listed under 'maps'", errors);
  if (ia->second >= ib->second) {
    errors.Fail(
        b.key, b.line,
        "expected a map listed after '" + o.a + "' under 'maps' (a before b), got '" + o.b + "'");
  }
  if (truth.maps[ia->second].building != truth.maps[ib->second].building) {
    errors.Fail(b.key, b.line,
                "'" + o.a + "' and '" + o.b + "' are maps of different buildings ('" +
                    truth.maps[ia->second].building + "', '" + truth.maps[ib->second].building +
                    "'); overlaps are listed within one building");
  }
  o.cells = ReadInteger(overlap.Require("cells", "a cell count"), 0,
                        std::numeric_limits<long long>::max(), errors);
  o.share = ReadNumber(overlap.Require("share", "a share in [0, 1]"), 0, 1, false, errors);
  return o;
}

}  // namespace

GroundTruth LoadTruth(const fs::path& path) {
  const YamlErrors errors(path);
  const YAML::Node root = ParseYamlText(ReadYamlFileText(path, "truth file", errors), errors);
  if (!root.IsMap()) {
    errors.Fail(
        "expected a truth file (a mapping with format, seed, buildings, maps, overlaps), "
        "got " +
        Describe(root));
  }
  // A report.json parses as YAML too: the two files of `eval` given the other way round.
  if (root["components"] && !root["format"]) {
    errors.Fail(
        "expected a truth file; this is a report.json of `fleetmerge merge` (`fleetmerge eval "
        "REPORT TRUTH` takes the report first)");
  }
  const YamlField top{root, "", root.Mark().is_null() ? 1 : root.Mark().line + 1};
  const YamlMapping file(top, {"format", "seed", "buildings", "maps", "overlaps"}, "a mapping",
                         errors);
  const YamlField format = file.Require("format", std::string("'") + kFormat + "'");
  if (!format.value.IsScalar() || format.value.Scalar() != kFormat) {
    FailExpected(format, std::string("'") + kFormat + "'", errors);
  }
  GroundTruth truth;
  truth.seed = static_cast<std::uint32_t>(
      ReadInteger(file.Require("seed", "an integer"), 0, UINT32_MAX, errors));

  const YamlField buildings = file.Require("buildings", "a list of buildings");
  RequireList(buildings, "a list of buildings {name, source}", errors);
  NameIndex building_names("building");
  for (std::size_t i = 0; i < buildings.value.size(); ++i) {
    const YamlField element = ListElement(buildings, i);
    truth.buildings.push_back(ReadBuilding(element, errors));
    building_names.Add(truth.buildings.back().name, element, errors);
  }

  const YamlField maps = file.Require("maps", "a non-empty list of maps");
  if (!maps.value.IsSequence() || maps.value.size() == 0) {
    FailExpected(maps, "a non-empty list of maps", errors);
  }
  NameIndex map_names("map");
  std::map<std::string, std::size_t> map_index;
  for (std::size_t i = 0; i < maps.value.size(); ++i) {
    const YamlField element = ListElement(maps, i);
    truth.maps.push_back(ReadMap(element, path.parent_path(), building_names, errors));
    map_names.Add(truth.maps.back().name, element, errors);
    map_index[truth.maps.back().name] = i;
  }

  if (const auto overlaps = file.Find("overlaps")) {
    RequireList(*overlaps, "a list of overlaps {a, b, cells, share}", errors);
    std::map<std::pair<std::string, std::string>, int> seen;
    for (std::size_t i = 0; i < overlaps->value.size(); ++i) {
      const YamlField element = ListElement(*overlaps, i);
      truth.overlaps.push_back(ReadOverlap(element, map_index, truth, errors));
      const auto [it, inserted] = seen.emplace(
          std::make_pair(truth.overlaps.back().a, truth.overlaps.back().b), element.line);
      if (!inserted) {
        errors.Fail(element.key, element.line,
                    "the pair '" + it->first.first + "', '" + it->first.second +
                        "' appears twice (first at line " + std::to_string(it->second) + ")");
      }
    }
  }
  return truth;
}

}  // namespace fleetmerge
