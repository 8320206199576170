// fleetmerge as a library: the one public header of the installed package.
//
//   find_package(fleetmerge CONFIG REQUIRED)
//   target_link_libraries(app PRIVATE fleetmerge::fleetmerge)
//
//   #include <fleetmerge/fleetmerge.hpp>
//   const fleetmerge::Map a = fleetmerge::LoadMap("robot1/map.yaml");
//   const fleetmerge::Map b = fleetmerge::LoadMap("robot2/map.yaml");
//   for (const fleetmerge::Hypothesis& h : fleetmerge::Pair(a, b)) { ... }  // best first
//
// The header needs nothing but the C++17 standard library: OpenCV, Eigen, Ceres, OctoMap and
// yaml-cpp stay inside libfleetmerge.so. Every result equals what the `fleetmerge` command prints
// for the same inputs and options (`fleetmerge pair --json`, report.json of `fleetmerge merge`).
// Errors are std::invalid_argument for arguments that break the documented contract and
// std::runtime_error (with the command's message, naming the file and what was wrong) for bad
// input files and failed jobs.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "fleetmerge/version.hpp"  // FLEETMERGE_VERSION_MAJOR, ..._STRING: this header's version

namespace fleetmerge {

// The library's version, "MAJOR.MINOR.PATCH" (CMake's project version): FLEETMERGE_VERSION_STRING
// of the build that made libfleetmerge.so.
std::string Version();

// A planar pose: metres and radians.
struct Pose2D {
  double x = 0.0;
  double y = 0.0;
  double yaw = 0.0;
};

// An occupancy grid map in ROS nav_msgs/OccupancyGrid convention: `data` holds width x height
// cells row by row, row 0 at the origin (the bottom row of a map_server image); -1 is unknown and
// 0..100 the occupancy probability in percent. `origin` is the pose of cell (0, 0)'s outer corner
// in the map frame (OccupancyGrid info.origin, yaw from its quaternion).
//
// fleetmerge works on three states, as map_server does with its default thresholds: a cell is
// occupied above 65, free below 19.6 (free_thresh 0.196), unknown otherwise. Maps fleetmerge
// returns hold only 100, 0 and -1.
class Map {
 public:
  Map() = default;
  // Throws std::invalid_argument unless data.size() == width * height, width and height are
  // positive, resolution is finite and > 0, origin is finite and every cell is -1 or 0..100.
  Map(std::vector<std::int8_t> data, int width, int height, double resolution_m, Pose2D origin = {},
      std::string name = "");

  const std::vector<std::int8_t>& data() const { return data_; }
  int width() const { return width_; }
  int height() const { return height_; }
  double resolution() const { return resolution_m_; }  // metres per cell
  const Pose2D& origin() const { return origin_; }
  // Used in merge results and report.json; LoadMap names a map after its file stem.
  const std::string& name() const { return name_; }
  void set_name(std::string name) { name_ = std::move(name); }
  // A fixed (base) map never moves in Merge: `pose` is its map frame in the merged frame, which
  // is its frame (job files' `fixed: true`, `pose: [x, y, yaw]`). The first fixed map is the
  // reference. The merged map keeps every cell a fixed map knows; the others fill the rest.
  // set_fixed throws std::invalid_argument, naming the map, for a non-finite pose, a yaw beyond 2
  // pi in magnitude (radians, not degrees), or a pose other than the identity with fixed == false
  // (a job file's `pose` without `fixed: true`).
  bool fixed() const { return fixed_; }
  const Pose2D& pose() const { return pose_; }
  void set_fixed(bool fixed, Pose2D pose = {});
  // A known start pose (job files' `initial_pose`, `initial_pose_sigma`): the map frame's pose in
  // the site frame in which every map's prior is given (with fixed maps, theirs), with its sigmas
  // (metres, radians; default 0.5 m and 10 deg). Merge refuses a pair whose hypotheses all
  // contradict two maps' known poses beyond 3 sigma, and places a map that overlaps no other at
  // its prior (MapPlacement::placed_by "prior"). set_initial_pose throws std::invalid_argument,
  // naming the map, for a non-finite pose, a sigma that is not finite and > 0, a yaw beyond
  // 2 pi in magnitude or a yaw sigma beyond pi (radians, not degrees); a fixed map
  // with an initial pose is refused by Merge. clear_initial_pose removes it.
  const std::optional<Pose2D>& initial_pose() const { return initial_pose_; }
  double initial_pose_sigma_m() const { return initial_pose_sigma_m_; }
  double initial_pose_sigma_rad() const { return initial_pose_sigma_rad_; }
  void set_initial_pose(Pose2D pose, double sigma_m = kDefaultInitialPoseSigmaM,
                        double sigma_rad = kDefaultInitialPoseSigmaRad);
  void clear_initial_pose() { initial_pose_.reset(); }
  static constexpr double kDefaultInitialPoseSigmaM = 0.5;
  static constexpr double kDefaultInitialPoseSigmaRad = 0.17453292519943295;  // 10 deg
  // The cell (i, j) (column i, row j from the origin), -1 outside the map.
  std::int8_t at(int i, int j) const;

 private:
  std::vector<std::int8_t> data_;
  int width_ = 0;
  int height_ = 0;
  double resolution_m_ = 0.0;
  Pose2D origin_;
  std::string name_;
  bool fixed_ = false;
  Pose2D pose_;
  std::optional<Pose2D> initial_pose_;
  double initial_pose_sigma_m_ = kDefaultInitialPoseSigmaM;
  double initial_pose_sigma_rad_ = kDefaultInitialPoseSigmaRad;
};

// Reads a map_server YAML (with its PGM/PNG image), an OctoMap octree (.bt, .ot: its 2-D floor
// plan, as `fleetmerge merge` uses it) or a ROS 1 / ROS 2 bag with one OccupancyGrid topic (its
// last map). Named as `fleetmerge merge --out` names it (the file stem). Throws
// std::runtime_error naming the file on bad input.
Map LoadMap(const std::string& path);

// Writes `yaml_path` and a trinary PGM beside it (same stem), as map_server's map_saver does,
// each atomically.
void SaveMap(const Map& map, const std::string& yaml_path);

// A known start pose given by map name (Options::initial_poses): as Map::set_initial_pose.
struct InitialPose {
  Pose2D pose;
  double sigma_m = Map::kDefaultInitialPoseSigmaM;
  double sigma_rad = Map::kDefaultInitialPoseSigmaRad;
};

// Parameters of Pair and Merge. Defaults are the command line's.
struct Options {
  int hypotheses = 4;       // per pair: Pair returns them (`pair -n`), Merge keeps them (job key
                            // hypotheses_per_pair) for its edges and report
  double resolution = 0.0;  // Merge: compare and composite at this (0: the finest map's)
  double omega_threshold = 0.9;     // Merge: best omega a pair needs to become an edge (Eq. 1)
  int min_overlap_cells = 5000;     // Merge: cells known in both maps an edge needs
  double min_wall_agreement = 0.8;  // Merge: symmetric wall agreement an edge needs
  // Merge: an edge that is the only link between two groups of maps (of three or more) needs
  // these walls: chance matches of a look-alike building pass the thresholds above. Lower it for
  // maps from different SLAM systems, whose true walls agree less (0.83-0.88 measured)
  double min_bridge_wall_agreement = 0.89;
  std::string fusion = "log-odds";  // Merge: log-odds | max | vote
  std::string reference;  // Merge: the reference map's name (empty: the first fixed map, else the
                          // first map; with fixed maps only the first fixed map)
  int threads = 0;        // Pair and Merge: threads (0: all cores); same results
  bool refine = true;     // false: Carpin's hypotheses without the local refinement
  std::string translation = "correlation";   // correlation (2-D FFT) | spectra (paper's X/Y)
  std::int64_t max_map_cells = 100'000'000;  // Merge of files: larger images are refused
  double octree_band_min = 0.3;  // Merge of octrees: floor plan height band above the floor (m)
  double octree_band_max = 1.8;
  // Merge: keep the pairs' hypotheses in this folder and reuse them when the same maps come
  // again (empty: no cache); at most cache_max_mb MiB, least recently used entries evicted.
  // Results are the same with and without it.
  std::string cache_dir;
  std::int64_t cache_max_mb = 1024;
  // MergeFiles: fixed maps with their poses and known start poses, by map name, as `merge
  // --fixed NAME=x,y,yaw --initial-pose NAME=x,y,yaw[,m,rad]` (a bag's or octree's maps too).
  // Merge of Maps takes them from each Map (set_fixed, set_initial_pose) and refuses these.
  std::map<std::string, Pose2D> fixed;
  std::map<std::string, InitialPose> initial_poses;
};

// One transformation of b's map frame into a's: the pose of b's frame in a's frame, its
// acceptance index omega (Eq. 1 of Carpin's paper, 0..1) and the evidence behind it.
struct Hypothesis {
  double x = 0.0;
  double y = 0.0;
  double yaw = 0.0;
  double omega = 0.0;
  std::int64_t overlap_cells = 0;  // cells known in both maps under this pose
  double wall_agreement = 0.0;     // share of walls landing near walls, the worse of both ways
};

// A pair's hypotheses, best first, and how decisively the best won. It iterates (and indexes)
// its hypotheses.
struct PairHypotheses {
  std::vector<Hypothesis> hypotheses;
  // The best's lead in evidence over the runner-up, in nats (ln of the likelihood ratio of the
  // two poses); +infinity without a runner-up; negative when the runner-up is clearly worse on
  // omega (the paper's ranking decided) yet has more evidence.
  double margin = 0.0;
  // The runner-up is a different pose that the maps cannot tell apart from the best: the answer
  // is a coin toss (a repetitive building); confirm it another way (a third map, a prior).
  bool ambiguous = false;

  auto begin() const { return hypotheses.begin(); }
  auto end() const { return hypotheses.end(); }
  std::size_t size() const { return hypotheses.size(); }
  bool empty() const { return hypotheses.empty(); }
  const Hypothesis& front() const { return hypotheses.front(); }
  const Hypothesis& operator[](std::size_t k) const { return hypotheses[k]; }
};

// The hypotheses that overlay map b on map a, best first, at most options.hypotheses of them:
// what `fleetmerge pair --json -n N a b` prints. Ranked by their evidence among those tied on
// omega (docs/method.md). Maps of different resolutions are compared at the finer one. Empty
// when a map has no occupied cell. Pair has no cache: a non-empty options.cache_dir is
// std::invalid_argument.
PairHypotheses Pair(const Map& a, const Map& b, const Options& options = {});

// Where one map went.
struct MapPlacement {
  std::string name;
  int component = 0;
  Pose2D pose;  // the map's frame in its component's merged frame (the reference map's frame;
                // with fixed maps or priors the site frame)
  // What placed it: "fixed", "reference", "pairs", "prior" (only its initial pose links it to
  // the rest of its component) or "unmerged" (alone in its component).
  std::string placed_by;
};

// The decision on one pair of maps (a before b in input order).
struct PairDecision {
  std::string a, b;
  double omega = 0.0;  // best hypothesis
  bool accepted = false;
  std::int64_t overlap_cells = 0;
  double wall_agreement = 0.0;
  std::string note;                    // why it was refused or dropped, when it was
  std::vector<Hypothesis> hypotheses;  // b's frame in a's, best first
};

struct Component {
  int id = 0;
  std::vector<std::string> maps;
  std::string reference;
  std::optional<Map> merged;  // two or more maps, a one-map job, or a fixed map alone
};

struct MergeResult {
  std::vector<MapPlacement> maps;  // in input order
  std::vector<Component> components;
  std::vector<PairDecision> pairs;
  // report.json's contents (JSON text): the names above and everything else it holds.
  std::string report_json;
};

// Merges a fleet's maps in memory; names must be distinct (an empty name becomes "map<k>",
// 1-based). With `out_dir`, also writes the usual result set there (merged maps, previews,
// report.json), replaced as a whole, as `fleetmerge merge --out` does.
MergeResult Merge(const std::vector<Map>& maps, const Options& options = {},
                  const std::string& out_dir = "");

// Merges map files (map_server YAMLs, octrees) exactly as `fleetmerge merge --out DIR files...`
// does, octrees included (merged_<c>.bt). Maps are named after their file stems; options.fixed
// and options.initial_poses name them (std::invalid_argument for a name that is no map's, a
// map in both, a pose or sigma set_fixed or set_initial_pose would refuse, or a reference
// other than the first fixed map).
MergeResult MergeFiles(const std::vector<std::string>& paths, const Options& options = {},
                       const std::string& out_dir = "");

}  // namespace fleetmerge
