#include <yaml-cpp/yaml.h>

#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "io/truth_file.hpp"

namespace fleetmerge {

void SaveTruth(const GroundTruth& truth, const std::filesystem::path& path) {
  YAML::Emitter out;
  out.SetDoublePrecision(17);  // poses round-trip exactly
  out << YAML::Comment(
      "fleetmerge ground truth: pose of each map's frame in its building's frame (m, rad)");
  out << YAML::BeginMap;
  out << YAML::Key << "format" << YAML::Value << "fleetmerge-truth-1";
  out << YAML::Key << "seed" << YAML::Value << truth.seed;
  out << YAML::Key << "buildings" << YAML::Value << YAML::BeginSeq;
  for (const auto& b : truth.buildings) {
    out << YAML::Flow << YAML::BeginMap << YAML::Key << "name" << YAML::Value << b.name << YAML::Key
        << "source" << YAML::Value << b.source << YAML::EndMap;
  }
  out << YAML::EndSeq;
  out << YAML::Key << "maps" << YAML::Value << YAML::BeginSeq;
  for (const auto& m : truth.maps) {
    out << YAML::Flow << YAML::BeginMap;
    out << YAML::Key << "name" << YAML::Value << m.name;
    out << YAML::Key << "file" << YAML::Value << m.file.generic_string();
    out << YAML::Key << "building" << YAML::Value << m.building;
    out << YAML::Key << "resolution" << YAML::Value << m.resolution_m;
    out << YAML::Key << "pose" << YAML::Value << YAML::BeginMap;
    out << YAML::Key << "x" << YAML::Value << m.T_building_map.x_m();
    out << YAML::Key << "y" << YAML::Value << m.T_building_map.y_m();
    out << YAML::Key << "yaw" << YAML::Value << m.T_building_map.yaw_rad();
    out << YAML::EndMap << YAML::EndMap;
  }
  out << YAML::EndSeq;
  out << YAML::Key << "overlaps" << YAML::Value << YAML::BeginSeq;
  for (const auto& o : truth.overlaps) {
    out << YAML::Flow << YAML::BeginMap << YAML::Key << "a" << YAML::Value << o.a << YAML::Key
        << "b" << YAML::Value << o.b << YAML::Key << "cells" << YAML::Value << o.cells << YAML::Key
        << "share" << YAML::Value << o.share << YAML::EndMap;
  }
  out << YAML::EndSeq << YAML::EndMap;
  if (!out.good())
    throw Error(path.string() + ": cannot write ground truth: " + out.GetLastError());
  WriteFileAtomically(path, std::string(out.c_str()) + "\n");
}

}  // namespace fleetmerge
