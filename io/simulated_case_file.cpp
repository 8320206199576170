#include "io/simulated_case_file.hpp"

#include <yaml-cpp/yaml.h>

#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "io/map_io.hpp"

namespace fleetmerge {
namespace {

std::string JobYaml(const SimulatedCase& simulated) {
  YAML::Emitter out;
  out.SetDoublePrecision(17);  // the priors as computed, to the last bit
  out << YAML::Comment(
      "fleetmerge simulate: merge the simulated robot maps (truth.yaml has the answer)");
  out << YAML::BeginMap;
  out << YAML::Key << "name" << YAML::Value << "simulated";
  out << YAML::Key << "maps" << YAML::Value << YAML::BeginSeq;
  if (simulated.base) {
    out << YAML::BeginMap << YAML::Key << "path" << YAML::Value
        << simulated.base->truth.file.string() << YAML::Key << "fixed" << YAML::Value << true
        << YAML::EndMap;
  }
  for (std::size_t k = 0; k < simulated.names.size(); ++k) {
    const std::string file = simulated.names[k] + ".yaml";
    if (!HasPrior(simulated.priors, static_cast<int>(k))) {
      out << file;
      continue;
    }
    const PosePrior& prior = *simulated.priors[k];
    const Pose2& T = prior.T_site_map;
    out << YAML::Flow << YAML::BeginMap << YAML::Key << "path" << YAML::Value << file << YAML::Key
        << "initial_pose" << YAML::Value << YAML::Flow << YAML::BeginSeq << T.x_m() << T.y_m()
        << T.yaw_rad() << YAML::EndSeq << YAML::Key << "initial_pose_sigma" << YAML::Value
        << YAML::Flow << YAML::BeginSeq << prior.translation_sigma_m << prior.yaw_sigma_rad
        << YAML::EndSeq << YAML::EndMap;
  }
  out << YAML::EndSeq;
  out << YAML::Key << "output" << YAML::Value << "merged";
  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

}  // namespace

GroundTruth WrittenTruth(const SimulatedCase& simulated) {
  GroundTruth truth = simulated.truth;
  if (simulated.base) {
    truth.maps.insert(truth.maps.begin(), simulated.base->truth);
    truth.overlaps.insert(truth.overlaps.begin(), simulated.base->overlaps.begin(),
                          simulated.base->overlaps.end());
  }
  return truth;
}

WrittenCase WriteSimulatedCase(const SimulatedCase& simulated, const std::filesystem::path& dir,
                               const std::vector<std::filesystem::path>& protected_inputs) {
  if (simulated.maps.size() != simulated.names.size() ||
      simulated.maps.size() != simulated.truth.maps.size()) {
    throw Error("simulated case: maps, names and truth maps differ in number");
  }
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw Error(dir.string() + ": cannot create the output folder: " + ec.message());
  WrittenCase written;
  written.truth_yaml = dir / "truth.yaml";
  written.job_yaml = dir / "job.yaml";
  for (const auto& name : simulated.names) {
    written.map_yamls.push_back(dir / (name + ".yaml"));
    CheckNotAnInput(written.map_yamls.back(), protected_inputs);
    CheckNotAnInput(dir / (name + ".pgm"), protected_inputs);
  }
  if (simulated.base) {
    written.base_yaml = dir / simulated.base->truth.file;
    CheckNotAnInput(written.base_yaml, protected_inputs);
    CheckNotAnInput(std::filesystem::path(written.base_yaml).replace_extension(".pgm"),
                    protected_inputs);
  }
  CheckNotAnInput(written.truth_yaml, protected_inputs);
  CheckNotAnInput(written.job_yaml, protected_inputs);

  for (std::size_t k = 0; k < simulated.maps.size(); ++k) {
    SaveMap(simulated.maps[k], written.map_yamls[k], protected_inputs);
  }
  if (simulated.base) SaveMap(simulated.base->map, written.base_yaml, protected_inputs);
  SaveTruth(WrittenTruth(simulated), written.truth_yaml);
  WriteFileAtomically(written.job_yaml, JobYaml(simulated), protected_inputs);
  return written;
}

}  // namespace fleetmerge
