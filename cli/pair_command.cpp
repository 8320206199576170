#include "cli/pair_command.hpp"

#include <cmath>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <ostream>

#include "core/error.hpp"
#include "io/map_inputs.hpp"
#include "io/map_io.hpp"
#include "io/resampled_size.hpp"
#include "pipeline/composite.hpp"
#include "pipeline/preview.hpp"

namespace fleetmerge {
namespace {

struct MergedFiles {
  std::filesystem::path yaml, preview;
};

// Composites a (identity) and b (at the best hypothesis) and writes map + preview atomically,
// never over an input file.
MergedFiles WriteMerged(const PairCommand& command, const LoadedMap& a, const LoadedMap& b,
                        const PairResult& result) {
  const std::filesystem::path& dir = *command.out_dir;
  std::filesystem::create_directories(dir);
  const std::vector<CompositeInput> inputs = {{&a.grid, Pose2()},
                                              {&b.grid, result.hypotheses.front().T_a_b}};
  const OccupancyGrid merged = Composite(inputs, result.resolution_m);
  std::vector<std::filesystem::path> protect;  // the inputs (a bag's map has no image path)
  for (const auto& p :
       {a.metadata.yaml_path, a.metadata.image_path, b.metadata.yaml_path, b.metadata.image_path}) {
    if (!p.empty()) protect.push_back(p);
  }
  MergedFiles files{dir / "merged.yaml", dir / "merged_preview.png"};
  SaveMap(merged, files.yaml, protect);
  SaveImage(ColourPreview(inputs, merged), files.preview, protect);
  return files;
}

// "robot1 (robot1.bag topic /map)": the name merge would give, and where the map came from.
std::string Describe(const JobMap& map) {
  return map.name + " (" + map.source.string() + (map.topic.empty() ? "" : " topic " + map.topic) +
         ")";
}

void PrintText(const std::vector<JobMap>& maps, const PairResult& result, std::ostream& out) {
  out << "a: " << Describe(maps[0]) << "\nb: " << Describe(maps[1]) << "\n";
  if (result.resampled) {
    out << "note: maps have different resolutions; compared at the finer, " << result.resolution_m
        << " m\n";
  }
  if (result.hypotheses.empty()) {
    out << "no hypothesis: a map has no occupied cell\n";
    return;
  }
  out << "pose of b's map frame in a's map frame, best first:\n"
      << "  #      x [m]      y [m]  yaw [rad]  yaw [deg]   omega\n";
  int rank = 1;
  for (const auto& h : result.hypotheses) {
    out << std::fixed << std::setw(3) << rank++ << std::setprecision(3) << std::setw(11)
        << h.T_a_b.x_m() << std::setw(11) << h.T_a_b.y_m() << std::setprecision(4) << std::setw(11)
        << h.T_a_b.yaw_rad() << std::setprecision(2) << std::setw(11)
        << h.T_a_b.yaw_rad() * 180.0 / M_PI << std::setprecision(4) << std::setw(8) << h.omega
        << "\n";
  }
  out.unsetf(std::ios::floatfield);
}

}  // namespace

int RunPairCommand(const PairCommand& command, std::ostream& out) {
  std::vector<JobMap> maps;
  for (const auto& path : {command.a_yaml, command.b_yaml}) {
    std::vector<JobMap> expanded = ExpandMapInputs({{path, path, "", command.topics}});
    if (expanded.size() != 1) {
      std::string topics;
      for (const JobMap& m : expanded) topics += (topics.empty() ? "" : ", ") + m.topic;
      throw Error(path.string() + ": has " + std::to_string(expanded.size()) + " map topics (" +
                  topics + "); pick one with --topic");
    }
    maps.push_back(expanded.front());
  }
  // Named together, as merge --out names them (r1/map.yaml, r2/map.yaml: r1, r2).
  std::vector<MapInput> both;
  for (const JobMap& m : maps) {
    both.push_back(
        {m.source, m.path, "",
         m.topic.empty() ? std::vector<std::string>{} : std::vector<std::string>{m.topic}});
  }
  std::error_code ec;
  const bool same =
      std::filesystem::equivalent(maps[0].path, maps[1].path, ec) && maps[0].topic == maps[1].topic;
  if (!same) maps = ExpandMapInputs(both);  // a map paired with itself keeps its one name
  const LoadedMap a = LoadJobMap(maps[0]);
  const LoadedMap b = LoadJobMap(maps[1]);
  CheckResampledSizes({&a, &b}, 0.0, kDefaultMaxMapCells);
  PairOptions options = command.options;
  options.hypotheses.max_hypotheses = command.hypotheses;
  const PairResult result = MergePair(a.grid, b.grid, options);

  std::optional<MergedFiles> files;
  if (command.out_dir && !result.hypotheses.empty()) files = WriteMerged(command, a, b, result);

  if (command.json) {
    nlohmann::json j = {{"a", command.a_yaml.string()},
                        {"b", command.b_yaml.string()},
                        {"a_name", maps[0].name},
                        {"b_name", maps[1].name},
                        {"hypotheses", nlohmann::json::array()}};
    for (const auto& h : result.hypotheses) {
      j["hypotheses"].push_back({{"x", h.T_a_b.x_m()},
                                 {"y", h.T_a_b.y_m()},
                                 {"yaw", h.T_a_b.yaw_rad()},
                                 {"omega", h.omega}});
    }
    j["resolution"] = result.resolution_m;
    if (files) j["merged_map"] = files->yaml.string();
    out << j.dump(2) << "\n";
  } else {
    PrintText(maps, result, out);
    if (files) {
      out << "merged map: " << files->yaml.string() << "\npreview:    " << files->preview.string()
          << "\n";
    }
  }
  return 0;
}

}  // namespace fleetmerge
