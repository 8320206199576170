#include "cli/pair_command.hpp"

#include <CLI/CLI.hpp>
#include <cmath>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>

#include "cli/cli_options.hpp"
#include "core/error.hpp"
#include "core/parallel.hpp"
#include "core/resample.hpp"
#include "io/map_inputs.hpp"
#include "io/map_io.hpp"
#include "io/resampled_size.hpp"
#include "pipeline/composite.hpp"
#include "pipeline/html_report.hpp"
#include "pipeline/preview.hpp"
#include "pipeline/report_json.hpp"

namespace fleetmerge {
namespace {

struct MergedFiles {
  std::filesystem::path yaml, preview, page;
};

// The pair's report.html (pipeline/html_report.hpp) in report.json's names: the two maps, one
// component merged at the best hypothesis, and the pair with all its hypotheses. `pair` applies
// no acceptance test, so the pair is shown accepted at hypothesis 1 with a note saying so.
HtmlReport PairPage(const PairCommand& command, const LoadedMap& a, const LoadedMap& b,
                    const PairResult& result, const OccupancyGrid& merged) {
  std::string name_a = command.a_yaml.stem().string(), name_b = command.b_yaml.stem().string();
  if (name_a == name_b) name_a += " (a)", name_b += " (b)";
  const Pose2 T_a_b = result.hypotheses.front().T_a_b;
  const auto pose = [](const Pose2& T) {
    return nlohmann::json{{"x", T.x_m()}, {"y", T.y_m()}, {"yaw", T.yaw_rad()}};
  };
  const nlohmann::json hypotheses = HypothesesJson(result.hypotheses);
  HtmlReport page;
  page.title = name_b + " on " + name_a;
  page.report = {
      {"job", "pair"},
      {"resolution", result.resolution_m},
      {"maps",
       {{{"name", name_a},
         {"source", command.a_yaml.string()},
         {"component", 0},
         {"pose", pose(Pose2())}},
        {{"name", name_b},
         {"source", command.b_yaml.string()},
         {"component", 0},
         {"pose", pose(T_a_b)}}}},
      {"components",
       {{{"id", 0},
         {"maps", {name_a, name_b}},
         {"reference", name_a},
         {"merged_map", "merged.yaml"}}}},
      {"pairs",
       {{{"a", name_a},
         {"b", name_b},
         {"omega", result.hypotheses.front().omega},
         {"accepted", true},
         {"overlap_cells", result.hypotheses.front().overlap_cells},
         {"wall_agreement", result.hypotheses.front().wall_agreement},
         {"ambiguous", result.ambiguous},
         {"margin", MarginJson(result.margin_nats)},
         {"edge_hypothesis", 0},
         {"hypotheses", hypotheses},
         {"note", "fleetmerge pair merges at the best hypothesis without an acceptance test"}}}}};
  for (const LoadedMap* map : {&a, &b}) {
    page.maps.push_back({&map->grid, map == &a ? Pose2() : T_a_b, map->metadata.yaml_path.string(),
                         map->grid.width(), map->grid.height(), map->metadata.resolution_m});
  }
  page.components.push_back({{0, 1}, &merged, "merged_preview.png"});
  return page;
}

// Composites a (identity) and b (at the best hypothesis) on a's cells, as merge does with its
// reference map, and writes map + preview atomically, never over an input file.
MergedFiles WriteMerged(const PairCommand& command, const LoadedMap& a, const LoadedMap& b,
                        const PairResult& result) {
  const std::filesystem::path& dir = *command.out_dir;
  std::filesystem::create_directories(dir);
  const double resolution_m = a.grid.geometry().resolution_m();
  // A finer b is coarsened first: a nearest-cell lookup would drop its one-cell walls.
  const OccupancyGrid b_at_a = ResampleToResolution(b.grid, resolution_m);
  const std::vector<CompositeInput> inputs = {{&a.grid, Pose2()},
                                              {&b_at_a, result.hypotheses.front().T_a_b}};
  PreviewColourer preview;  // coloured while compositing: the inputs are sampled once
  const OccupancyGrid merged = Composite(inputs, resolution_m, FusionMode::kLogOdds,
                                         command.threads, /*reference=*/0, &preview);
  std::vector<std::filesystem::path> protect;  // the inputs (a bag's map has no image path)
  for (const auto& p :
       {a.metadata.yaml_path, a.metadata.image_path, b.metadata.yaml_path, b.metadata.image_path}) {
    if (!p.empty()) protect.push_back(p);
  }
  MergedFiles files{dir / "merged.yaml", dir / "merged_preview.png", dir / kHtmlReportName};
  SaveMap(merged, files.yaml, protect);
  SaveImage(preview.image(), files.preview, protect);
  WriteHtmlReport(PairPage(command, a, b, result, merged), dir, protect,  // the page last
                  command.threads);
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
      << "  #      x [m]      y [m]  yaw [rad]  yaw [deg]   omega  overlap  walls\n";
  int rank = 1;
  for (const auto& h : result.hypotheses) {
    out << std::fixed << std::setw(3) << rank++ << std::setprecision(3) << std::setw(11)
        << h.T_a_b.x_m() << std::setw(11) << h.T_a_b.y_m() << std::setprecision(4) << std::setw(11)
        << h.T_a_b.yaw_rad() << std::setprecision(2) << std::setw(11)
        << h.T_a_b.yaw_rad() * 180.0 / M_PI << std::setprecision(4) << std::setw(8) << h.omega
        << std::setw(9) << h.overlap_cells << std::setprecision(3) << std::setw(7)
        << h.wall_agreement << "\n";
  }
  if (result.ambiguous) {
    out << "AMBIGUOUS: hypotheses 1 and 2 are different poses that the maps cannot tell apart "
           "(evidence margin "
        << std::setprecision(2) << result.margin_nats
        << " nats); hypothesis 1 is a coin toss: confirm it with a third map or a known pose\n";
  }
  out.unsetf(std::ios::floatfield);
}

}  // namespace

CLI::App* AddPairCommand(CLI::App& app, PairCommand& command) {
  CLI::App* pair = app.add_subcommand(
      "pair", "Rank the transformations that overlay map B on map A (pose of B's frame in A's)");
  pair->add_option("a", command.a_yaml, "map A (map_server YAML, or a ROS 1/ROS 2 bag)")
      ->required();
  pair->add_option("b", command.b_yaml, "map B (map_server YAML, or a ROS 1/ROS 2 bag)")
      ->required();
  // Repeatable options take one value per occurrence (allow_extra_args(false)): by default
  // CLI11 lets a vector option swallow the map paths after it (`--fixed a a.yaml b.yaml`).
  pair->add_option("--topic", command.topics,
                   "bags: the nav_msgs/OccupancyGrid topic to read (repeatable)")
      ->allow_extra_args(false);
  pair->add_option("-n", command.hypotheses, "number of hypotheses")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  pair->add_option("--threads", command.threads, "threads (0: all cores)")->capture_default_str();
  pair->add_flag("--json", command.json, "print JSON instead of a table");
  pair->add_option("--out", command.out_dir,
                   "also write the merged map of the best hypothesis into this folder");
  AddMethodOptions(*pair, command.options);
  pair->add_option("--free-penalty", command.options.hypotheses.translation.free_penalty,
                   "translation search: weight of a wall on the other map's open space "
                   "(merge searches a fixed map's pairs with 0.25: a map inside a site map)")
      ->check(CLI::Range(0.0, 100.0))
      ->capture_default_str();

  return pair;
}

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
  // Both maps loaded at once; a failure names a before b (ParallelFor rethrows the lowest index).
  std::optional<LoadedMap> loaded[2];
  ParallelFor(2, command.threads, [&](std::size_t k) { loaded[k] = LoadJobMap(maps[k]); });
  const LoadedMap& a = *loaded[0];
  const LoadedMap& b = *loaded[1];
  CheckResampledSizes({&a, &b}, 0.0, kDefaultMaxMapCells);
  PairOptions options = command.options;
  options.hypotheses.max_hypotheses = command.hypotheses;
  const PairResult result = MergePair(a.grid, b.grid, options, command.threads);

  std::optional<MergedFiles> files;
  if (command.out_dir && !result.hypotheses.empty()) files = WriteMerged(command, a, b, result);

  if (command.json) {
    nlohmann::json j = {{"a", command.a_yaml.string()},
                        {"b", command.b_yaml.string()},
                        {"a_name", maps[0].name},
                        {"b_name", maps[1].name},
                        {"hypotheses", HypothesesJson(result.hypotheses)},
                        {"ambiguous", result.ambiguous},
                        {"margin", MarginJson(result.margin_nats)}};
    j["resolution"] = result.resolution_m;
    if (files) {
      j["merged_map"] = files->yaml.string();
      j["report_html"] = files->page.string();
    }
    out << j.dump(2) << "\n";
  } else {
    PrintText(maps, result, out);
    if (files) {
      out << "merged map: " << files->yaml.string() << "\npreview:    " << files->preview.string()
          << "\nreport:     " << files->page.string() << "\n";
    }
  }
  return 0;
}

}  // namespace fleetmerge
