#include "io/job_file.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <utility>

#include "core/error.hpp"
#include "io/bag_maps.hpp"
#include "io/map_inputs.hpp"
#include "io/map_names.hpp"
#include "io/map_yaml.hpp"
#include "io/octree_io.hpp"
#include "io/octree_job_keys.hpp"
#include "io/sampling_spec.hpp"
#include "io/yaml_errors.hpp"
#include "io/yaml_fields.hpp"

namespace fleetmerge {
namespace fs = std::filesystem;
namespace {

// clang-format off
const std::vector<std::string> kJobKeys = {
    "name", "maps", "output", "reference", "resolution", "threads", "hypotheses_per_pair",
    "omega_threshold", "min_overlap_cells", "min_wall_agreement", "min_bridge_wall_agreement",
    "refine", "seed", "hough", "translation", "pose_graph", "fusion", "octree", "max_map_cells",
    "tf_parent", "tf_child", "cache", "cache_max_mb"};
// clang-format on

SamplingOptions ReadSampling(const YamlField& field, const YamlErrors& errors) {
  const std::optional<SamplingOptions> sampling =
      field.value.IsScalar() ? ParseSamplingSpec(field.value.Scalar()) : std::nullopt;
  if (!sampling) FailExpected(field, kSamplingSpecExpected, errors);
  return *sampling;
}

// --- Options ---------------------------------------------------------------------------------

constexpr double kInf = std::numeric_limits<double>::infinity();

void ReadHough(const YamlField& field, HypothesisOptions& options, const YamlErrors& errors) {
  const YamlMapping hough(field, {"n_theta", "rho_step", "sampling"}, "a mapping", errors);
  if (auto f = hough.Find("n_theta")) options.hough.n_theta = ReadInteger(*f, 8, 3600, errors);
  if (auto f = hough.Find("rho_step")) {
    options.hough.rho_step_cells = ReadNumber(*f, 0.1, 100.0, false, errors);
  }
  if (auto f = hough.Find("sampling")) options.hough_sampling = ReadSampling(*f, errors);
}

void ReadTranslation(const YamlField& field, HypothesisOptions& options, const YamlErrors& errors) {
  const YamlMapping translation(field, {"method", "sampling"}, "a mapping", errors);
  if (auto f = translation.Find("method")) {
    options.translation.method =
        ReadChoice<TranslationMethod>(*f,
                                      {{"correlation", TranslationMethod::kCorrelation2D},
                                       {"spectra", TranslationMethod::kXySpectra}},
                                      errors);
  }
  if (auto f = translation.Find("sampling")) options.spectra_sampling = ReadSampling(*f, errors);
}

void ReadPoseGraph(const YamlField& field, PoseGraphOptions& options, const YamlErrors& errors) {
  const YamlMapping graph(
      field, {"loss", "loss_scale", "max_edge_yaw_error_deg", "max_edge_translation_error_m"},
      "a mapping", errors);
  if (auto f = graph.Find("loss")) {
    options.loss = ReadChoice<RobustLoss>(*f,
                                          {{"none", RobustLoss::kNone},
                                           {"huber", RobustLoss::kHuber},
                                           {"cauchy", RobustLoss::kCauchy}},
                                          errors);
  }
  if (auto f = graph.Find("loss_scale")) options.loss_scale = ReadNumber(*f, 0, kInf, true, errors);
  if (auto f = graph.Find("max_edge_yaw_error_deg")) {
    options.max_edge_yaw_error_rad = ReadNumber(*f, 0, kInf, true, errors) * M_PI / 180.0;
  }
  if (auto f = graph.Find("max_edge_translation_error_m")) {
    options.max_edge_translation_error_m = ReadNumber(*f, 0, kInf, true, errors);
  }
}

void ReadOptions(const YamlMapping& job, FleetOptions& options, const YamlErrors& errors) {
  HypothesisOptions& hypotheses = options.pair.hypotheses;
  if (auto f = job.Find("resolution")) options.resolution_m = ReadNumber(*f, 0, kInf, true, errors);
  if (auto f = job.Find("threads")) options.threads = ReadInteger(*f, 0, INT_MAX, errors);
  if (auto f = job.Find("hypotheses_per_pair")) {
    hypotheses.max_hypotheses = ReadInteger(*f, 1, 100, errors);
  }
  if (auto f = job.Find("omega_threshold")) {
    options.omega_threshold = ReadNumber(*f, 0, 1, false, errors);
  }
  if (auto f = job.Find("min_wall_agreement")) {
    options.min_wall_agreement = ReadNumber(*f, 0, 1, false, errors);
  }
  if (auto f = job.Find("min_overlap_cells")) {
    options.min_overlap_cells = ReadInteger(*f, 0, INT_MAX, errors);
  }
  if (auto f = job.Find("min_bridge_wall_agreement")) {
    options.min_bridge_wall_agreement = ReadNumber(*f, 0, 1, false, errors);
  }
  if (auto f = job.Find("max_map_cells")) {
    options.max_map_cells = ReadInteger(*f, 1, std::numeric_limits<std::int64_t>::max(), errors);
  }
  if (auto f = job.Find("refine")) options.pair.refine = ReadBool(*f, errors);
  if (auto f = job.Find("hough")) ReadHough(*f, hypotheses, errors);
  if (auto f = job.Find("translation")) ReadTranslation(*f, hypotheses, errors);
  {  // as on the command line (default 0): Hough seed, spectra seed + 1
    const auto f = job.Find("seed");
    const auto seed =
        f ? static_cast<std::uint32_t>(ReadInteger(*f, 0, UINT32_MAX, errors)) : std::uint32_t(0);
    hypotheses.hough_sampling.seed = seed;
    hypotheses.spectra_sampling.seed = seed + 1;  // also after a `sampling` spec (seed 0)
  }
  if (auto f = job.Find("pose_graph")) ReadPoseGraph(*f, options.pose_graph, errors);
  if (auto f = job.Find("octree")) ReadOctreeOptions(*f, options.octree, errors);
  if (auto f = job.Find("fusion")) {
    options.fusion = ReadChoice<FusionMode>(*f,
                                            {{"log_odds", FusionMode::kLogOdds},
                                             {"max", FusionMode::kMax},
                                             {"vote", FusionMode::kVote}},
                                            errors);
  }
}

// --- Maps and jobs ---------------------------------------------------------------------------

fs::path Resolve(const fs::path& folder, const fs::path& source) {
  return source.is_absolute() ? source : folder / source;
}

// The path two entries naming one file share (symbolic links, "..", a trailing "/" resolved).
fs::path Canonical(const fs::path& path) {
  std::error_code ec;
  fs::path canonical = fs::weakly_canonical(path, ec);
  if (ec) canonical = fs::absolute(path).lexically_normal();
  return canonical.has_filename() ? canonical : canonical.parent_path();
}

// One entry of `maps`, with where its name came from (for errors).
struct ListedMap {
  JobMap map;
  fs::path canonical;
  YamlField entry;
  YamlField name;  // the entry itself when the name is the file's
};

// An entry: a path, or {path, name, topic, fixed, pose, initial_pose, initial_pose_sigma}; a
// bag entry without `topic` lists every map topic.
struct MapEntry {
  MapInput input;
  YamlField entry;
  YamlField name;
  bool fixed = false;
  Pose2 T_merged_map;
  std::optional<PosePrior> prior;
};

constexpr char kPoseExpected[] = "[x, y, yaw]: a list of 3 finite numbers (m, m, rad)";
constexpr char kSigmaExpected[] =
    "[metres, radians]: a list of 2 finite numbers > 0 (the prior's translation and yaw sigma)";

// A list of `count` finite numbers (positive ones if `positive`); `key` and `expected` name the
// list in an element's error.
std::vector<double> ReadNumbers(const YamlField& field, std::size_t count, const char* key,
                                const char* expected, bool positive, const YamlErrors& errors) {
  if (!field.value.IsSequence() || field.value.size() != count) {
    FailExpected(field, expected, errors);
  }
  std::vector<double> numbers;
  for (std::size_t i = 0; i < count; ++i) {
    const YamlField element = ListElement(field, i);
    double value = 0.0;
    if (!element.value.IsScalar() || element.value.Tag() == "!" ||
        !YAML::convert<double>::decode(element.value, value) || !std::isfinite(value) ||
        (positive && !(value > 0.0))) {
      FailExpected(element,
                   std::string(positive ? "a finite number > 0 (" : "a finite number (") + key +
                       " is " + expected + ")",
                   errors);
    }
    numbers.push_back(value);
  }
  return numbers;
}

// A fixed map's `pose` or a map's `initial_pose`: its map frame in the merged frame, as
// map_server's `origin` is written.
Pose2 ReadPose(const YamlField& field, const char* key, const YamlErrors& errors) {
  const std::vector<double> xyz = ReadNumbers(field, 3, key, kPoseExpected, false, errors);
  if (std::abs(xyz[2]) > kMaxYawRad) {
    FailExpected(
        ListElement(field, 2),
        std::string("a yaw in radians, at most 2 pi in magnitude: ") + YawLooksLikeDegrees(xyz[2]),
        errors);
  }
  return Pose2(xyz[0], xyz[1], xyz[2]);
}

MapEntry ReadMapEntry(const YamlField& entry, const fs::path& folder, const YamlErrors& errors) {
  const std::string expected =
      "a map YAML or bag path, or a mapping {path, name, topic, fixed, pose, initial_pose, "
      "initial_pose_sigma}";
  MapEntry listed{{}, entry, entry, false, Pose2(), std::nullopt};
  std::string source;
  if (entry.value.IsMap()) {
    const YamlMapping map(
        entry, {"path", "name", "topic", "fixed", "pose", "initial_pose", "initial_pose_sigma"},
        expected, errors);
    source =
        ReadString(map.Require("path", "a map YAML or bag path"), "a map YAML or bag path", errors);
    if (auto f = map.Find("name")) {
      listed.input.name = ReadString(*f, "a map name", errors);
      listed.name = *f;
    }
    if (auto f = map.Find("topic")) {
      listed.input.topics = {ReadString(*f, "a bag topic (nav_msgs/OccupancyGrid)", errors)};
    }
    if (auto f = map.Find("fixed")) listed.fixed = ReadBool(*f, errors);
    if (auto f = map.Find("pose")) {
      listed.T_merged_map = ReadPose(*f, "pose", errors);
      if (!listed.fixed) {
        errors.Fail(f->key, f->line,
                    "'pose' is the pose of a fixed map; add 'fixed: true' or remove 'pose' "
                    "(a robot's known start pose is 'initial_pose')");
      }
    }
    if (auto f = map.Find("initial_pose")) {
      listed.prior = PosePrior{ReadPose(*f, "initial_pose", errors)};
      if (listed.fixed) {
        errors.Fail(f->key, f->line,
                    "a fixed map's pose is its 'pose', exactly; remove 'initial_pose' or "
                    "'fixed: true'");
      }
    }
    if (auto f = map.Find("initial_pose_sigma")) {
      const std::vector<double> sigma =
          ReadNumbers(*f, 2, "initial_pose_sigma", kSigmaExpected, true, errors);
      if (sigma[1] > kMaxYawSigmaRad) {
        FailExpected(
            ListElement(*f, 1),
            std::string("a yaw sigma in radians, at most pi: ") + YawLooksLikeDegrees(sigma[1]),
            errors);
      }
      if (!listed.prior) {
        errors.Fail(f->key, f->line,
                    listed.fixed ? "a fixed map's pose is exact: remove 'initial_pose_sigma'"
                                 : "'initial_pose_sigma' is the uncertainty of an "
                                   "'initial_pose'; add 'initial_pose: [x, y, yaw]' or remove "
                                   "'initial_pose_sigma'");
      }
      listed.prior->translation_sigma_m = sigma[0];
      listed.prior->yaw_sigma_rad = sigma[1];
    }
  } else {
    source = ReadString(entry, expected, errors);
  }
  listed.input.source = source;
  listed.input.path = Resolve(folder, source);
  return listed;
}

// The maps of one entry (a bag's topics), checked: the metadata only (or an octree's header,
// a bag's topic list), so that a bad map stops the file before work.
std::vector<ListedMap> ExpandEntry(const MapEntry& entry, const YamlErrors& errors) {
  std::vector<ListedMap> maps;
  try {
    const fs::path& path = entry.input.path;
    if (!entry.input.topics.empty() && !IsBagPath(path)) {
      throw Error(path.string() + ": 'topic' is given but this is not a bag");
    }
    if (IsBagPath(path)) {
      for (JobMap& map : ExpandMapInputs({entry.input})) {
        map.name = entry.input.name;  // names are given over the whole list (ReadMaps)
        map.fixed = entry.fixed;
        map.T_merged_map = entry.T_merged_map;
        map.prior = entry.prior;
        maps.push_back({std::move(map), Canonical(path), entry.entry, entry.name});
      }
    } else {
      if (IsOctreePath(path)) {
        CheckOctreeFile(path);
      } else {
        ReadMapYaml(path);
      }
      maps.push_back({{entry.input.name, entry.input.source, path, "", entry.fixed,
                       entry.T_merged_map, entry.prior},
                      Canonical(path),
                      entry.entry,
                      entry.name});
    }
  } catch (const Error& e) {
    errors.Fail(entry.entry.key, entry.entry.line, e.what());
  }
  return maps;
}

void CheckDistinctMaps(const std::vector<ListedMap>& maps, const YamlErrors& errors) {
  for (std::size_t j = 1; j < maps.size(); ++j) {
    for (std::size_t i = 0; i < j; ++i) {
      const std::string first =
          maps[i].entry.key + " (line " + std::to_string(maps[i].entry.line) + ")";
      if (maps[j].map.name == maps[i].map.name) {
        errors.Fail(maps[j].name.key, maps[j].name.line,
                    "map name '" + maps[j].map.name + "' is also the name of " + first +
                        "; give each map a unique 'name'");
      }
      if (maps[j].canonical == maps[i].canonical && maps[j].map.topic == maps[i].map.topic) {
        errors.Fail(maps[j].entry.key, maps[j].entry.line,
                    "'" + maps[j].map.source.string() + "'" +
                        (maps[j].map.topic.empty() ? "" : " topic " + maps[j].map.topic) +
                        " is the same file as " + first);
      }
    }
  }
}

std::vector<JobMap> ReadMaps(const YamlField& field, const fs::path& folder,
                             const YamlErrors& errors) {
  if (!field.value.IsSequence() || field.value.size() == 0) {
    FailExpected(field, "a non-empty list of map YAML files", errors);
  }
  std::vector<ListedMap> listed;
  for (std::size_t i = 0; i < field.value.size(); ++i) {
    for (ListedMap& map :
         ExpandEntry(ReadMapEntry(ListElement(field, i), folder, errors), errors)) {
      listed.push_back(std::move(map));
    }
  }
  // Maps without a `name`: named from their paths, never as a given name (io/map_names.hpp).
  std::vector<MapNameInput> unnamed;
  std::vector<std::string> taken;
  std::map<fs::path, int> maps_per_bag;
  for (const ListedMap& m : listed) {
    if (!m.map.topic.empty()) ++maps_per_bag[m.canonical];
  }
  for (const ListedMap& m : listed) {
    if (!m.map.name.empty()) {
      taken.push_back(m.map.name);
    } else {
      unnamed.push_back({NamingPath(m.map.path), maps_per_bag[m.canonical] > 1 ? m.map.topic : ""});
    }
  }
  std::vector<std::string> names;
  try {
    names = UniqueMapNames(unnamed, taken);
  } catch (const Error& e) {
    errors.Fail(field.key, field.line, e.what());
  }
  std::size_t k = 0;
  for (ListedMap& m : listed) {
    if (m.map.name.empty()) m.map.name = names[k++];
  }
  CheckDistinctMaps(listed, errors);
  std::vector<JobMap> maps;
  for (ListedMap& entry : listed) maps.push_back(std::move(entry.map));
  return maps;
}

std::string ReadReference(const YamlMapping& job, const std::vector<JobMap>& maps,
                          const YamlErrors& errors) {
  const JobMap* first_fixed = FirstFixedMap(maps);
  const std::optional<YamlField> field = job.Find("reference");
  if (!field) return first_fixed ? first_fixed->name : maps.front().name;
  std::vector<std::string> names;
  for (const JobMap& map : maps) names.push_back("'" + map.name + "'");
  const std::string expected = "the name of one of the job's maps (" + JoinWords(names) + ")";
  const std::string reference = ReadString(*field, expected, errors);
  if (first_fixed && reference != first_fixed->name) {
    FailExpected(*field,
                 "the first fixed map '" + first_fixed->name +
                     "' (with fixed maps the merged frame is theirs), or no 'reference'",
                 errors);
  }
  for (const JobMap& map : maps) {
    if (map.name == reference) return reference;
  }
  FailExpected(*field, expected, errors);
}

// A job and where its name and output came from (for the checks across jobs).
struct ListedJob {
  Job job;
  fs::path canonical_output;
  YamlField name;  // the job's mapping when the name is the default
  YamlField output;
};

ListedJob ReadJob(const YamlField& field, int number, const fs::path& job_file,
                  const YamlErrors& errors) {
  const YamlMapping job(field, kJobKeys, "a job: a mapping with 'maps' and 'output'", errors);
  const fs::path folder = job_file.parent_path();
  ListedJob listed{{}, {}, field, {}};
  Job& result = listed.job;
  result.job_file = job_file;
  result.name = "job " + std::to_string(number);
  if (auto f = job.Find("name")) {
    result.name = ReadString(*f, "a job name", errors);
    listed.name = *f;
  }
  result.maps = ReadMaps(job.Require("maps", "a non-empty list of map YAML files"), folder, errors);
  listed.output = job.Require("output", "an output folder");
  result.output_dir = Resolve(folder, ReadString(listed.output, "an output folder", errors));
  listed.canonical_output = Canonical(result.output_dir);
  std::error_code ec;
  if (fs::exists(result.output_dir, ec) && !fs::is_directory(result.output_dir, ec)) {
    errors.Fail(listed.output.key, listed.output.line,
                "'" + result.output_dir.string() + "' exists and is not a folder");
  }
  result.reference = ReadReference(job, result.maps, errors);
  if (auto f = job.Find("tf_parent")) result.tf_parent_frame = ReadString(*f, "a frame id", errors);
  if (auto f = job.Find("tf_child")) {
    result.tf_child_frame = ReadString(*f, "a frame id pattern with {name}", errors);
  }
  ReadOptions(job, result.options, errors);
  if (auto f = job.Find("cache")) {
    result.options.cache_dir = Resolve(folder, ReadString(*f, "a cache folder", errors));
    if (fs::exists(result.options.cache_dir, ec) &&
        !fs::is_directory(result.options.cache_dir, ec)) {
      errors.Fail(
          f->key, f->line,
          "cache folder '" + result.options.cache_dir.string() + "' exists and is not a folder");
    }
  }
  if (auto f = job.Find("cache_max_mb")) {
    result.options.cache_max_mb = ReadInteger(*f, 1, kLargestCacheMaxMb, errors);
    // As --cache-max-mb without a cache: a bound on nothing is a mistake, not a setting,
    // unless `merge --cache DIR` gives the job its cache (checked there).
    if (!job.Find("cache")) {
      result.cache_bound_without_cache = errors.Message(
          f->key, f->line,
          "a size bound without a cache: give the job a 'cache' folder (or run it with "
          "--cache DIR), or leave cache_max_mb out");
    }
  }
  return listed;
}

void CheckDistinctJobs(const std::vector<ListedJob>& jobs, const YamlErrors& errors) {
  for (std::size_t j = 1; j < jobs.size(); ++j) {
    for (std::size_t i = 0; i < j; ++i) {
      const std::string first =
          "job '" + jobs[i].job.name + "' (line " + std::to_string(jobs[i].name.line) + ")";
      if (jobs[j].job.name == jobs[i].job.name) {
        errors.Fail(jobs[j].name.key, jobs[j].name.line,
                    "job name '" + jobs[j].job.name + "' is also the name of " + first);
      }
      if (jobs[j].canonical_output == jobs[i].canonical_output) {
        errors.Fail(jobs[j].output.key, jobs[j].output.line,
                    "'" + jobs[j].job.output_dir.string() + "' is also the output folder of " +
                        first + "; each job needs its own");
      }
    }
  }
}

// The jobs of the file: the root itself (one job) or the elements of `jobs`.
std::vector<ListedJob> ReadJobs(const YAML::Node& root, const fs::path& yaml_path,
                                const YamlErrors& errors) {
  const YamlField top{root, "", root.Mark().is_null() ? 1 : root.Mark().line + 1};
  if (!root.IsMap()) {
    errors.Fail(
        "expected a job (a mapping with 'maps' and 'output') or 'jobs:' with a list of "
        "jobs, got " +
        Describe(root));
  }
  if (!root["jobs"]) return {ReadJob(top, 1, yaml_path, errors)};
  const YamlMapping file(top, {"jobs"}, "a mapping", errors);
  const YamlField list = file.Require("jobs", "a list of jobs");
  if (!list.value.IsSequence() || list.value.size() == 0) {
    FailExpected(list, "a non-empty list of jobs", errors);
  }
  std::vector<ListedJob> jobs;
  for (std::size_t i = 0; i < list.value.size(); ++i) {
    jobs.push_back(ReadJob(ListElement(list, i), static_cast<int>(i) + 1, yaml_path, errors));
  }
  return jobs;
}

}  // namespace

std::vector<Job> LoadJobFile(const fs::path& yaml_path) {
  const YamlErrors errors(yaml_path);
  const YAML::Node root = ParseYamlText(ReadYamlFileText(yaml_path, "job file", errors), errors);
  std::vector<ListedJob> listed = ReadJobs(root, yaml_path, errors);
  CheckDistinctJobs(listed, errors);
  std::vector<Job> jobs;
  for (ListedJob& entry : listed) jobs.push_back(std::move(entry.job));
  return jobs;
}

}  // namespace fleetmerge
