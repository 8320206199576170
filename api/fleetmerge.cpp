// The public API (api/include/fleetmerge/fleetmerge.hpp) on top of the merging job: conversions
// between the public Map (nav_msgs/OccupancyGrid cells) and core's three-state OccupancyGrid, and
// the same calls the `fleetmerge` command makes, so that results are the command's.
#include "fleetmerge/fleetmerge.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "io/bag_maps.hpp"
#include "io/map_inputs.hpp"
#include "io/map_io.hpp"
#include "io/octree_io.hpp"
#include "pipeline/job_run.hpp"
#include "pipeline/octree_maps.hpp"
#include "pipeline/pair_merge.hpp"

namespace fleetmerge {
namespace {

// map_server's default trinary thresholds (io/map_io.hpp), on OccupancyGrid's percentages.
constexpr double kOccupiedThreshPercent = 65.0;
constexpr double kFreeThreshPercent = 19.6;

void Require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("fleetmerge: " + what);
}

bool Finite(const Pose2D& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.yaw);
}

OccupancyGrid ToGrid(const Map& map) {
  Require(map.width() > 0 && map.height() > 0,
          "map '" + map.name() + "' is empty (build it with Map(data, width, height, ...))");
  const GridGeometry geometry(map.resolution(), {map.width(), map.height()},
                              Pose2(map.origin().x, map.origin().y, map.origin().yaw));
  cv::Mat1b cells(map.height(), map.width());
  const std::vector<std::int8_t>& data = map.data();
  for (int j = 0; j < map.height(); ++j) {
    std::uint8_t* row = cells.ptr<std::uint8_t>(j);  // row j from the bottom, as data's
    for (int i = 0; i < map.width(); ++i) {
      const int v = data[static_cast<std::size_t>(j) * map.width() + i];
      CellState state = CellState::kUnknown;
      if (v >= 0) {
        if (v > kOccupiedThreshPercent)
          state = CellState::kOccupied;
        else if (v < kFreeThreshPercent)
          state = CellState::kFree;
      }
      row[i] = static_cast<std::uint8_t>(state);
    }
  }
  return OccupancyGrid(geometry, cells);
}

Map FromGrid(const OccupancyGrid& grid, std::string name) {
  std::vector<std::int8_t> data(static_cast<std::size_t>(grid.width()) * grid.height());
  for (int j = 0; j < grid.height(); ++j) {
    const std::uint8_t* row = grid.cells().ptr<std::uint8_t>(j);
    for (int i = 0; i < grid.width(); ++i) {
      const auto state = static_cast<CellState>(row[i]);
      data[static_cast<std::size_t>(j) * grid.width() + i] = state == CellState::kOccupied ? 100
                                                             : state == CellState::kFree   ? 0
                                                                                           : -1;
    }
  }
  const Pose2& T = grid.geometry().T_map_grid();
  return Map(std::move(data), grid.width(), grid.height(), grid.geometry().resolution_m(),
             {T.x_m(), T.y_m(), T.yaw_rad()}, std::move(name));
}

Pose2D ToPublic(const Pose2& T) { return {T.x_m(), T.y_m(), T.yaw_rad()}; }

// Options -> the command line's FleetOptions (cli/main.cpp, cli/cli_options.cpp).
FleetOptions ToFleetOptions(const Options& o) {
  Require(o.hypotheses >= 1 && o.hypotheses <= 100,
          "hypotheses must be 1..100, got " + std::to_string(o.hypotheses));
  Require(std::isfinite(o.resolution) && o.resolution >= 0.0,
          "resolution must be a finite number >= 0 (0: the finest map's)");
  Require(o.omega_threshold >= 0.0 && o.omega_threshold <= 1.0, "omega_threshold must be in 0..1");
  Require(o.min_overlap_cells >= 0, "min_overlap_cells must be >= 0");
  Require(o.min_wall_agreement >= 0.0 && o.min_wall_agreement <= 1.0,
          "min_wall_agreement must be in 0..1");
  Require(o.min_bridge_wall_agreement >= 0.0 && o.min_bridge_wall_agreement <= 1.0,
          "min_bridge_wall_agreement must be in 0..1");
  Require(o.threads >= 0, "threads must be >= 0 (0: all cores)");
  Require(o.max_map_cells > 0, "max_map_cells must be > 0");
  Require(o.cache_max_mb >= 1 && o.cache_max_mb <= kLargestCacheMaxMb,
          "cache_max_mb must be in 1.." + std::to_string(kLargestCacheMaxMb));
  Require(std::isfinite(o.octree_band_min) && std::isfinite(o.octree_band_max) &&
              o.octree_band_min < o.octree_band_max,
          "octree_band_min must be below octree_band_max");
  FleetOptions f;
  f.resolution_m = o.resolution;
  f.omega_threshold = o.omega_threshold;
  f.min_overlap_cells = o.min_overlap_cells;
  f.min_wall_agreement = o.min_wall_agreement;
  f.min_bridge_wall_agreement = o.min_bridge_wall_agreement;
  f.threads = o.threads;
  f.max_map_cells = o.max_map_cells;
  f.cache_dir = o.cache_dir;
  f.cache_max_mb = o.cache_max_mb;
  f.octree.band_min_m = o.octree_band_min;
  f.octree.band_max_m = o.octree_band_max;
  if (o.fusion == "log-odds") {
    f.fusion = FusionMode::kLogOdds;
  } else if (o.fusion == "max") {
    f.fusion = FusionMode::kMax;
  } else if (o.fusion == "vote") {
    f.fusion = FusionMode::kVote;
  } else {
    Require(false, "fusion must be log-odds, max or vote, got '" + o.fusion + "'");
  }
  HypothesisOptions& h = f.pair.hypotheses;
  if (o.translation == "correlation") {
    h.translation.method = TranslationMethod::kCorrelation2D;
  } else if (o.translation == "spectra") {
    h.translation.method = TranslationMethod::kXySpectra;
  } else {
    Require(false, "translation must be correlation or spectra, got '" + o.translation + "'");
  }
  f.pair.refine = o.refine;
  // As the command line seeds sampling (cli/cli_options.cpp, --seed 0).
  h.hough_sampling.seed = 0;
  h.spectra_sampling.seed = 1;
  h.max_hypotheses = o.hypotheses;
  return f;
}

MergeResult ToResult(const Job& job, const JobOutcome& outcome) {
  const FleetResult& r = outcome.result;
  MergeResult out;
  for (std::size_t m = 0; m < job.maps.size(); ++m) {
    out.maps.push_back({job.maps[m].name, r.component_of[m], ToPublic(r.T_component_map[m]),
                        PlacedByName(r.placed_by[m])});
  }
  for (std::size_t c = 0; c < r.components.size(); ++c) {
    Component component;
    component.id = static_cast<int>(c);
    for (int m : r.components[c].maps) component.maps.push_back(job.maps[m].name);
    component.reference = job.maps[r.components[c].reference].name;
    if (r.components[c].merged) {
      component.merged = FromGrid(*r.components[c].merged, "merged_" + std::to_string(c));
    }
    out.components.push_back(std::move(component));
  }
  for (const PairOutcome& p : r.pairs) {
    PairDecision d;
    d.a = job.maps[p.a].name;
    d.b = job.maps[p.b].name;
    d.omega = p.best_omega();
    d.accepted = p.accepted;
    d.overlap_cells = p.overlap_cells;
    d.wall_agreement = p.wall_agreement;
    d.note = p.note;
    for (const PairHypothesis& h : p.hypotheses) {
      d.hypotheses.push_back({h.T_a_b.x_m(), h.T_a_b.y_m(), h.T_a_b.yaw_rad(), h.omega});
    }
    out.pairs.push_back(std::move(d));
  }
  out.report_json = outcome.report.dump(2) + "\n";
  return out;
}

std::optional<std::string> Reference(const Options& options) {
  if (options.reference.empty()) return std::nullopt;
  return options.reference;
}

// The job's reference, once its maps know which are fixed: options.reference, else the first
// fixed map, else the first map; with fixed maps only the first fixed map may be named (as job
// files and the command line rule).
void SetReference(const Options& options, Job& job) {
  const JobMap* first_fixed = FirstFixedMap(job.maps);
  const std::string& first = first_fixed ? first_fixed->name : job.maps.front().name;
  job.reference = options.reference.empty() ? first : options.reference;
  bool found = false;
  for (const JobMap& m : job.maps) found = found || m.name == job.reference;
  Require(found, "reference '" + job.reference + "' is not one of the maps' names");
  Require(!first_fixed || job.reference == first,
          "reference '" + job.reference +
              "': with fixed maps the reference is the first fixed map, '" + first +
              "'; a reference given must be the first fixed map, or left empty");
}

}  // namespace

std::string Version() { return FLEETMERGE_VERSION_STRING; }

Map::Map(std::vector<std::int8_t> data, int width, int height, double resolution_m, Pose2D origin,
         std::string name)
    : data_(std::move(data)),
      width_(width),
      height_(height),
      resolution_m_(resolution_m),
      origin_(origin),
      name_(std::move(name)) {
  Require(width > 0 && height > 0, "map width and height must be > 0, got " +
                                       std::to_string(width) + " x " + std::to_string(height));
  Require(static_cast<std::int64_t>(width) * height <= kDefaultMaxMapCells,
          "map of " + std::to_string(width) + " x " + std::to_string(height) +
              " cells is larger than " + std::to_string(kDefaultMaxMapCells) + " cells");
  Require(data_.size() == static_cast<std::size_t>(width) * height,
          "map data holds " + std::to_string(data_.size()) +
              " cells, width x height = " + std::to_string(width) + " x " + std::to_string(height));
  Require(std::isfinite(resolution_m) && resolution_m > 0.0,
          "map resolution must be a finite number > 0 (metres per cell)");
  Require(Finite(origin), "map origin (x, y, yaw) must be finite");
  for (std::size_t k = 0; k < data_.size(); ++k) {
    Require(data_[k] >= -1 && data_[k] <= 100,
            "map cell " + std::to_string(k) + " (column " + std::to_string(k % width) + ", row " +
                std::to_string(k / width) + ") is " + std::to_string(data_[k]) +
                "; OccupancyGrid cells are -1 (unknown) or 0..100");
  }
}

namespace {

// The checks of Map::set_fixed (with fixed) and Options::fixed.
void CheckFixedPose(const std::string& name, const Pose2D& pose) {
  if (!std::isfinite(pose.x) || !std::isfinite(pose.y) || !std::isfinite(pose.yaw)) {
    throw std::invalid_argument("map '" + name + "': a fixed map's pose must be finite [x, y, " +
                                "yaw] (m, m, rad)");
  }
  if (std::abs(pose.yaw) > kMaxYawRad) {
    throw std::invalid_argument("map '" + name + "': a fixed map's pose yaw " +
                                YawLooksLikeDegrees(pose.yaw) +
                                "; expected radians, at most 2 pi in magnitude");
  }
}

// The checks of Map::set_initial_pose and Options::initial_poses.
void CheckInitialPose(const std::string& name, const Pose2D& pose, double sigma_m,
                      double sigma_rad) {
  if (!std::isfinite(pose.x) || !std::isfinite(pose.y) || !std::isfinite(pose.yaw)) {
    throw std::invalid_argument("map '" + name +
                                "': an initial pose must be finite [x, y, yaw] (m, m, rad)");
  }
  if (!std::isfinite(sigma_m) || !(sigma_m > 0.0) || !std::isfinite(sigma_rad) ||
      !(sigma_rad > 0.0)) {
    throw std::invalid_argument("map '" + name + "': an initial pose's sigmas [" +
                                std::to_string(sigma_m) + " m, " + std::to_string(sigma_rad) +
                                " rad] must be finite and > 0");
  }
  if (std::abs(pose.yaw) > kMaxYawRad) {
    throw std::invalid_argument("map '" + name + "': an initial pose's yaw " +
                                YawLooksLikeDegrees(pose.yaw) +
                                "; expected radians, at most 2 pi in magnitude");
  }
  if (sigma_rad > kMaxYawSigmaRad) {
    throw std::invalid_argument("map '" + name + "': an initial pose's yaw sigma " +
                                YawLooksLikeDegrees(sigma_rad) + "; expected radians, at most pi");
  }
}

}  // namespace

void Map::set_fixed(bool fixed, Pose2D pose) {
  CheckFixedPose(name_, pose);
  if (!fixed && (pose.x != 0.0 || pose.y != 0.0 || pose.yaw != 0.0)) {
    // As a job file refuses `pose` without `fixed: true`: it would be ignored.
    throw std::invalid_argument("map '" + name_ +
                                "': a pose is the pose of a fixed map; set it with "
                                "set_fixed(true, pose) (a robot's known start pose is "
                                "set_initial_pose)");
  }
  fixed_ = fixed;
  pose_ = pose;
}

void Map::set_initial_pose(Pose2D pose, double sigma_m, double sigma_rad) {
  CheckInitialPose(name_, pose, sigma_m, sigma_rad);
  initial_pose_ = pose;
  initial_pose_sigma_m_ = sigma_m;
  initial_pose_sigma_rad_ = sigma_rad;
}

std::int8_t Map::at(int i, int j) const {
  if (i < 0 || j < 0 || i >= width_ || j >= height_) return -1;
  return data_[static_cast<std::size_t>(j) * width_ + i];
}

Map LoadMap(const std::string& path) {
  const std::filesystem::path p(path);
  if (IsOctreePath(p)) {
    JobOctree octree;
    return FromGrid(LoadOctreeMap(p, OctreeOptions{}, octree).grid, p.stem().string());
  }
  // A bag (or a file of a ROS 2 bag) holding one map topic, named as `merge --out` names it.
  const std::vector<JobMap> maps = ExpandMapInputs({{p, p, "", {}}});
  if (maps.size() != 1) {
    throw Error(path + " holds " + std::to_string(maps.size()) +
                " map topics; LoadMap reads one: merge the bag (MergeFiles) or extract its "
                "topics (fleetmerge extract)");
  }
  return FromGrid(LoadJobMap(maps.front(), kDefaultMaxMapCells).grid, maps.front().name);
}

void SaveMap(const Map& map, const std::string& yaml_path) {
  const OccupancyGrid grid = ToGrid(map);
  SaveMap(grid, std::filesystem::path(yaml_path), {});
}

PairHypotheses Pair(const Map& a, const Map& b, const Options& options) {
  // Silently computing the pair anew would read as "the cache did not help".
  Require(options.cache_dir.empty(),
          "pair has no cache (cache_dir is merge's option: it keeps a fleet's pairs for re-runs); "
          "leave cache_dir out");
  const PairOptions pair_options = ToFleetOptions(options).pair;
  const OccupancyGrid grid_a = ToGrid(a), grid_b = ToGrid(b);
  const PairResult result = MergePair(grid_a, grid_b, pair_options, options.threads);
  PairHypotheses out;
  for (const PairHypothesis& h : result.hypotheses) {
    out.hypotheses.push_back({h.T_a_b.x_m(), h.T_a_b.y_m(), h.T_a_b.yaw_rad(), h.omega,
                              h.overlap_cells, h.wall_agreement});
  }
  out.margin = result.margin_nats;
  out.ambiguous = result.ambiguous;
  return out;
}

MergeResult Merge(const std::vector<Map>& maps, const Options& options,
                  const std::string& out_dir) {
  Require(!maps.empty(), "merge needs at least one map");
  Require(options.fixed.empty() && options.initial_poses.empty(),
          "options.fixed and options.initial_poses name map files (MergeFiles); a Map carries "
          "its own: set_fixed, set_initial_pose");
  const auto start = std::chrono::steady_clock::now();
  Job job;
  job.name = "merge";
  job.output_dir = out_dir;
  job.options = ToFleetOptions(options);
  std::vector<LoadedMap> loaded;
  for (std::size_t m = 0; m < maps.size(); ++m) {
    const std::string name =
        maps[m].name().empty() ? "map" + std::to_string(m + 1) : maps[m].name();
    for (const JobMap& earlier : job.maps) {
      Require(earlier.name != name, "two maps are named '" + name + "' (names must be distinct)");
    }
    JobMap job_map;  // in memory: no source file, no path
    job_map.name = name;
    job_map.fixed = maps[m].fixed();
    job_map.T_merged_map = Pose2(maps[m].pose().x, maps[m].pose().y, maps[m].pose().yaw);
    if (const auto& p = maps[m].initial_pose()) {
      Require(!maps[m].fixed(), "map '" + name +
                                    "': a fixed map's pose is its given pose, exactly; it has no "
                                    "initial pose (clear_initial_pose, or set_fixed(false))");
      job_map.prior = PosePrior{Pose2(p->x, p->y, p->yaw), maps[m].initial_pose_sigma_m(),
                                maps[m].initial_pose_sigma_rad()};
    }
    job.maps.push_back(job_map);
    LoadedMap l;
    l.grid = ToGrid(maps[m]);
    l.metadata.resolution_m = maps[m].resolution();
    loaded.push_back(std::move(l));
  }
  SetReference(options, job);
  JobRunOptions run;
  run.write = !out_dir.empty();
  return ToResult(job, RunLoadedJob(job, loaded, {}, MillisecondsSince(start), run));
}

namespace {

// Options::fixed and Options::initial_poses on a map list's job, by name, as `merge --fixed` and
// `--initial-pose` give them.
void ApplyNamedPoses(const Options& options, Job& job) {
  const auto named = [&job](const std::string& name, const char* key) -> JobMap& {
    for (JobMap& map : job.maps) {
      if (map.name == name) return map;
    }
    throw std::invalid_argument(std::string("options.") + key + ": no map is named '" + name +
                                "' (the maps: " + QuotedMapNames(job.maps) + ")");
  };
  for (const auto& [name, pose] : options.fixed) {
    CheckFixedPose(name, pose);
    JobMap& map = named(name, "fixed");
    map.fixed = true;
    map.T_merged_map = Pose2(pose.x, pose.y, pose.yaw);
  }
  for (const auto& [name, prior] : options.initial_poses) {
    CheckInitialPose(name, prior.pose, prior.sigma_m, prior.sigma_rad);
    JobMap& map = named(name, "initial_poses");
    if (map.fixed) {
      throw std::invalid_argument("map '" + name +
                                  "' is in options.fixed and options.initial_poses: a fixed "
                                  "map's pose is exact; give it in one of them");
    }
    map.prior = PosePrior{Pose2(prior.pose.x, prior.pose.y, prior.pose.yaw), prior.sigma_m,
                          prior.sigma_rad};
  }
}

}  // namespace

MergeResult MergeFiles(const std::vector<std::string>& paths, const Options& options,
                       const std::string& out_dir) {
  Require(!paths.empty(), "merge needs at least one map");
  const FleetOptions fleet_options = ToFleetOptions(options);
  const std::vector<std::filesystem::path> files(paths.begin(), paths.end());
  Job job = MapListJob(files, out_dir, Reference(options), fleet_options);
  ApplyNamedPoses(options, job);
  SetReference(options, job);
  JobRunOptions run;
  run.write = !out_dir.empty();
  return ToResult(job, RunJob(job, run));
}

}  // namespace fleetmerge
