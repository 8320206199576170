// LoadJobFile: the schema of configs/README.md, its defaults (FleetOptions{}), path resolution,
// and every way a job file is rejected before work starts. Each message must start with the job
// file's path and name the line and the key path (STYLE.md, "Errors").
#include "io/job_file.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "tests/io/io_test_util.hpp"
#include "tests/support/shared_data.hpp"

namespace fleetmerge {
namespace {

namespace fs = std::filesystem;
namespace ft = fleetmerge::testing;

using ft::Contains;
using ft::StartsWith;

void ExpectSameSampling(const SamplingOptions& a, const SamplingOptions& b) {
  EXPECT_EQ(a.mode, b.mode);
  EXPECT_EQ(a.fraction, b.fraction);
  EXPECT_EQ(a.step, b.step);
  EXPECT_EQ(a.seed, b.seed);
}

// Every field of FleetOptions (those a job file sets and those it leaves alone).
void ExpectSameOptions(const FleetOptions& a, const FleetOptions& b) {
  EXPECT_EQ(a.resolution_m, b.resolution_m);
  EXPECT_EQ(a.omega_threshold, b.omega_threshold);
  EXPECT_EQ(a.min_overlap_cells, b.min_overlap_cells);
  EXPECT_EQ(a.min_wall_agreement, b.min_wall_agreement);
  EXPECT_EQ(a.min_bridge_wall_agreement, b.min_bridge_wall_agreement);
  EXPECT_EQ(a.fusion, b.fusion);
  EXPECT_EQ(a.threads, b.threads);
  const HypothesisOptions& ha = a.pair.hypotheses;
  const HypothesisOptions& hb = b.pair.hypotheses;
  EXPECT_EQ(ha.hough.n_theta, hb.hough.n_theta);
  EXPECT_EQ(ha.hough.rho_step_cells, hb.hough.rho_step_cells);
  ExpectSameSampling(ha.hough_sampling, hb.hough_sampling);
  ExpectSameSampling(ha.spectra_sampling, hb.spectra_sampling);
  EXPECT_EQ(ha.rotation_peaks, hb.rotation_peaks);
  EXPECT_EQ(ha.translation.method, hb.translation.method);
  EXPECT_EQ(ha.translation.candidates, hb.translation.candidates);
  EXPECT_EQ(ha.max_hypotheses, hb.max_hypotheses);
  EXPECT_EQ(a.pair.refine, b.pair.refine);
  EXPECT_EQ(a.pair.refine_truncation_cells, b.pair.refine_truncation_cells);
  EXPECT_EQ(a.pair.candidates_per_hypothesis, b.pair.candidates_per_hypothesis);
  EXPECT_EQ(a.pose_graph.loss, b.pose_graph.loss);
  EXPECT_EQ(a.pose_graph.loss_scale, b.pose_graph.loss_scale);
  EXPECT_EQ(a.pose_graph.translation_sigma_m, b.pose_graph.translation_sigma_m);
  EXPECT_EQ(a.pose_graph.yaw_sigma_rad, b.pose_graph.yaw_sigma_rad);
  EXPECT_EQ(a.pose_graph.max_edge_yaw_error_rad, b.pose_graph.max_edge_yaw_error_rad);
  EXPECT_EQ(a.pose_graph.max_edge_translation_error_m, b.pose_graph.max_edge_translation_error_m);
  EXPECT_EQ(a.cache_dir, b.cache_dir);
  EXPECT_EQ(a.cache_max_mb, b.cache_max_mb);
}

// A folder with valid tiny maps maps/{a,b,c}.yaml and other/a.yaml (same stem as maps/a.yaml);
// each test writes its own job file.
class JobFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = ft::MakeTempDir("job_file");
    for (const char* folder : {"maps", "other"}) {
      fs::create_directories(dir_ / folder);
      ft::WriteFile(dir_ / folder / "tiny.pgm", "P2\n3 2\n255\n0 128 254\n205 255 100\n");
    }
    for (const char* name : {"a", "b", "c"}) {
      ft::WriteFile(dir_ / "maps" / (std::string(name) + ".yaml"), ft::MapYaml("tiny.pgm"));
    }
    ft::WriteFile(dir_ / "other" / "a.yaml", ft::MapYaml("tiny.pgm"));
  }

  fs::path Write(const std::string& text, const std::string& name = "job.yaml") const {
    ft::WriteFile(dir_ / name, text);
    return dir_ / name;
  }

  std::vector<Job> Load(const std::string& text) const { return LoadJobFile(Write(text)); }

  // LoadJobFile's message (a test failure if it throws nothing).
  std::string LoadError(const std::string& text) const {
    const fs::path path = Write(text);
    try {
      LoadJobFile(path);
    } catch (const fleetmerge::Error& e) {
      return e.what();
    }
    ADD_FAILURE() << "LoadJobFile accepted:\n" << text;
    return "";
  }

  // The message starts "<path>: line L: key 'key': " and contains `part`.
  void ExpectError(const std::string& text, int line, const std::string& key,
                   const std::string& part) const {
    SCOPED_TRACE(text);
    const std::string message = LoadError(text);
    EXPECT_TRUE(StartsWith(message, (dir_ / "job.yaml").string() + ": line " +
                                        std::to_string(line) + ": key '" + key + "': "));
    EXPECT_TRUE(Contains(message, part));
  }

  fs::path dir_;
};

// A minimal job's head: two maps and an output, then `extra` lines (line 4 onwards).
std::string Minimal(const std::string& extra = "") {
  return "maps: [maps/a.yaml, maps/b.yaml]\noutput: out\n# options\n" + extra;
}

// --- Valid files -----------------------------------------------------------------------------

TEST_F(JobFileTest, MinimalJobHasFleetOptionsDefaults) {
  const std::vector<Job> jobs = Load("maps:\n  - maps/a.yaml\noutput: out\n");
  ASSERT_EQ(jobs.size(), 1u);
  const Job& job = jobs[0];
  EXPECT_EQ(job.name, "job 1");
  EXPECT_EQ(job.job_file, dir_ / "job.yaml");
  ASSERT_EQ(job.maps.size(), 1u);  // a single map is its own merged map
  EXPECT_EQ(job.maps[0].name, "a");
  EXPECT_EQ(job.reference, "a");
  EXPECT_EQ(job.output_dir, dir_ / "out");
  ExpectSameOptions(job.options, FleetOptions{});
}

TEST_F(JobFileTest, EveryKeyIsParsedIntoItsField) {
  const std::vector<Job> jobs = Load(
      "name: corridor\n"
      "maps:\n"
      "  - maps/a.yaml\n"
      "  - {path: maps/b.yaml, name: second}\n"
      "  - path: maps/c.yaml\n"
      "output: results/corridor\n"
      "reference: second\n"
      "resolution: 0.1\n"
      "threads: 3\n"
      "hypotheses_per_pair: 7\n"
      "omega_threshold: 0.85\n"
      "min_overlap_cells: 500\n"
      "min_wall_agreement: 0.6\n"
      "min_bridge_wall_agreement: 0.85\n"
      "refine: false\n"
      "seed: 42\n"
      "hough: {n_theta: 360, rho_step: 2.5, sampling: 'random:0.5'}\n"
      "translation:\n"
      "  method: spectra\n"
      "  sampling: every:3\n"
      "pose_graph:\n"
      "  loss: huber\n"
      "  loss_scale: 2\n"
      "  max_edge_yaw_error_deg: 2.0\n"
      "  max_edge_translation_error_m: 0.4\n"
      "fusion: vote\n");
  ASSERT_EQ(jobs.size(), 1u);
  const Job& job = jobs[0];
  EXPECT_EQ(job.name, "corridor");
  ASSERT_EQ(job.maps.size(), 3u);
  EXPECT_EQ(job.maps[0].name, "a");
  EXPECT_EQ(job.maps[1].name, "second");
  EXPECT_EQ(job.maps[2].name, "c");
  EXPECT_EQ(job.output_dir, dir_ / "results/corridor");
  EXPECT_EQ(job.reference, "second");
  const FleetOptions& o = job.options;
  EXPECT_EQ(o.resolution_m, 0.1);
  EXPECT_EQ(o.threads, 3);
  EXPECT_EQ(o.pair.hypotheses.max_hypotheses, 7);
  EXPECT_EQ(o.omega_threshold, 0.85);
  EXPECT_EQ(o.min_overlap_cells, 500);
  EXPECT_EQ(o.min_wall_agreement, 0.6);
  EXPECT_EQ(o.min_bridge_wall_agreement, 0.85);
  EXPECT_FALSE(o.pair.refine);
  const HypothesisOptions& h = o.pair.hypotheses;
  EXPECT_EQ(h.hough.n_theta, 360);
  EXPECT_EQ(h.hough.rho_step_cells, 2.5);
  EXPECT_EQ(h.hough_sampling.mode, SamplingMode::kRandomFraction);
  EXPECT_EQ(h.hough_sampling.fraction, 0.5);
  EXPECT_EQ(h.hough_sampling.seed, 42u);  // as on the command line: Hough seed, spectra seed + 1
  EXPECT_EQ(h.translation.method, TranslationMethod::kXySpectra);
  EXPECT_EQ(h.spectra_sampling.mode, SamplingMode::kEveryKth);
  EXPECT_EQ(h.spectra_sampling.step, 3);
  EXPECT_EQ(h.spectra_sampling.seed, 43u);
  EXPECT_EQ(o.pose_graph.loss, RobustLoss::kHuber);
  EXPECT_EQ(o.pose_graph.loss_scale, 2.0);
  EXPECT_NEAR(o.pose_graph.max_edge_yaw_error_rad, 2.0 * M_PI / 180.0, 1e-15);
  EXPECT_EQ(o.pose_graph.max_edge_translation_error_m, 0.4);
  EXPECT_EQ(o.fusion, FusionMode::kVote);
}

TEST_F(JobFileTest, EnumsTakeEveryValue) {
  for (const auto& [text, loss] :
       std::vector<std::pair<std::string, RobustLoss>>{{"none", RobustLoss::kNone},
                                                       {"huber", RobustLoss::kHuber},
                                                       {"cauchy", RobustLoss::kCauchy}}) {
    EXPECT_EQ(Load(Minimal("pose_graph: {loss: " + text + "}\n"))[0].options.pose_graph.loss, loss);
  }
  for (const auto& [text, mode] :
       std::vector<std::pair<std::string, FusionMode>>{{"log_odds", FusionMode::kLogOdds},
                                                       {"max", FusionMode::kMax},
                                                       {"vote", FusionMode::kVote}}) {
    EXPECT_EQ(Load(Minimal("fusion: " + text + "\n"))[0].options.fusion, mode);
  }
  EXPECT_EQ(Load(Minimal("translation: {method: correlation}\n"))[0]
                .options.pair.hypotheses.translation.method,
            TranslationMethod::kCorrelation2D);
  EXPECT_EQ(
      Load(Minimal("hough: {sampling: all}\n"))[0].options.pair.hypotheses.hough_sampling.mode,
      SamplingMode::kAll);
}

// Without `seed:` a job seeds sampling as `merge --out` and Python do (--seed 0: Hough 0,
// spectra 1), also after a `sampling` spec.
TEST_F(JobFileTest, TheDefaultSeedIsTheCommandLines) {
  for (const std::string extra : {"", "translation: {sampling: \"random:0.5\"}\n"}) {
    const HypothesisOptions h = Load(Minimal(extra))[0].options.pair.hypotheses;
    EXPECT_EQ(h.hough_sampling.seed, 0u) << extra;
    EXPECT_EQ(h.spectra_sampling.seed, 1u) << extra;
  }
}

TEST_F(JobFileTest, RangeEndsAreAccepted) {
  const FleetOptions o =
      Load(Minimal("hough: {n_theta: 3600, rho_step: 0.1}\n"
                   "omega_threshold: 0\nmin_overlap_cells: 0\nthreads: 0\n"
                   "hypotheses_per_pair: 100\nseed: 4294967295\nrefine: true\n"))[0]
          .options;
  EXPECT_EQ(o.pair.hypotheses.hough.n_theta, 3600);
  EXPECT_EQ(o.pair.hypotheses.hough.rho_step_cells, 0.1);
  EXPECT_EQ(o.omega_threshold, 0.0);
  EXPECT_EQ(o.min_overlap_cells, 0);
  EXPECT_EQ(o.pair.hypotheses.max_hypotheses, 100);
  EXPECT_EQ(o.pair.hypotheses.hough_sampling.seed, 4294967295u);
  EXPECT_EQ(o.pair.hypotheses.spectra_sampling.seed, 0u);  // wraps, as on the command line
  EXPECT_EQ(Load(Minimal("hough: {n_theta: 8, rho_step: 100}\nomega_threshold: 1\n"))[0]
                .options.pair.hypotheses.hough.n_theta,
            8);
}

TEST_F(JobFileTest, SeveralJobsInOneFile) {
  const std::vector<Job> jobs = Load(
      "jobs:\n"
      "  - maps: [maps/a.yaml, maps/b.yaml]\n"
      "    output: out/first\n"
      "    threads: 2\n"
      "  - name: second\n"
      "    maps: [maps/b.yaml, maps/c.yaml]\n"
      "    output: out/second\n"
      "    reference: c\n");
  ASSERT_EQ(jobs.size(), 2u);
  EXPECT_EQ(jobs[0].name, "job 1");
  EXPECT_EQ(jobs[1].name, "second");
  EXPECT_EQ(jobs[0].options.threads, 2);
  EXPECT_EQ(jobs[1].options.threads, 0);  // options do not leak from one job to the next
  EXPECT_EQ(jobs[0].reference, "a");
  EXPECT_EQ(jobs[1].reference, "c");
  EXPECT_EQ(jobs[1].output_dir, dir_ / "out/second");
}

TEST_F(JobFileTest, RelativePathsResolveAgainstTheJobFilesFolder) {
  fs::create_directories(dir_ / "configs");
  const fs::path job_file = dir_ / "configs" / "job.yaml";
  ft::WriteFile(job_file, "maps: [../maps/a.yaml, '" + (dir_ / "maps/b.yaml").string() +
                              "']\noutput: ../out/x\n");
  const Job job = LoadJobFile(job_file).at(0);
  EXPECT_EQ(job.maps[0].source, fs::path("../maps/a.yaml"));  // as written
  EXPECT_EQ(job.maps[0].path, dir_ / "configs" / "../maps/a.yaml");
  EXPECT_TRUE(fs::equivalent(job.maps[0].path, dir_ / "maps/a.yaml"));
  EXPECT_EQ(job.maps[1].source, dir_ / "maps/b.yaml");  // absolute: kept
  EXPECT_EQ(job.maps[1].path, dir_ / "maps/b.yaml");
  EXPECT_EQ(job.output_dir, dir_ / "configs" / "../out/x");
}

TEST_F(JobFileTest, SameStemInTwoFoldersIsFineWithNames) {
  const Job job =
      Load("maps:\n  - maps/a.yaml\n  - {path: other/a.yaml, name: a2}\noutput: out\n").at(0);
  EXPECT_EQ(job.maps[1].name, "a2");
}

// --- Rejections: values ----------------------------------------------------------------------

TEST_F(JobFileTest, BriefExampleNamesJobIndexLineAndKey) {
  std::string text = "jobs:\n";
  for (int i = 0; i < 3; ++i) {
    text += "  - maps: [maps/a.yaml]\n    output: out/" + std::to_string(i) + "\n";
  }
  text += "    hough:\n      n_theta: abc\n";  // jobs[2] (0-based), line 9
  EXPECT_EQ(LoadError(text), (dir_ / "job.yaml").string() +
                                 ": line 9: key 'jobs[2].hough.n_theta': expected an integer in "
                                 "[8, 3600], got 'abc'");
}

struct BadValue {
  std::string extra;  // appended to Minimal(), starting on line 4
  std::string key;
  std::string part;
  int line = 4;
};

TEST_F(JobFileTest, EveryValueIsTypeAndRangeChecked) {
  const std::string sampling = "expected 'all', 'random:F' with F in (0, 1] or 'every:K'";
  const std::vector<BadValue> cases = {
      {"resolution: 0\n", "resolution", "expected a number > 0, got '0'"},
      {"resolution: -0.05\n", "resolution", "a number > 0"},
      {"resolution: .inf\n", "resolution", "got '.inf'"},
      {"resolution: .nan\n", "resolution", "got '.nan'"},
      {"resolution: fine\n", "resolution", "got 'fine'"},
      {"resolution: [0.05]\n", "resolution", "got a list of 1 element"},
      {"resolution:\n", "resolution", "got an empty value"},
      {"threads: -1\n", "threads", "expected an integer >= 0, got '-1'"},
      {"threads: 1.5\n", "threads", "expected an integer >= 0"},
      {"threads: 99999999999\n", "threads", "expected an integer >= 0"},
      {"hypotheses_per_pair: 0\n", "hypotheses_per_pair", "expected an integer in [1, 100]"},
      {"hypotheses_per_pair: 101\n", "hypotheses_per_pair", "in [1, 100], got '101'"},
      {"omega_threshold: 1.1\n", "omega_threshold", "expected a number in [0, 1], got '1.1'"},
      {"min_wall_agreement: -0.1\n", "min_wall_agreement",
       "expected a number in [0, 1], got '-0.1'"},
      {"min_bridge_wall_agreement: 1.5\n", "min_bridge_wall_agreement",
       "expected a number in [0, 1], got '1.5'"},

      {"omega_threshold: -0.1\n", "omega_threshold", "in [0, 1]"},
      {"omega_threshold: .nan\n", "omega_threshold", "in [0, 1]"},
      {"omega_threshold: '0.9'\n", "omega_threshold", "got '0.9' (quoted, so a string)"},
      {"min_overlap_cells: -1\n", "min_overlap_cells", "expected an integer >= 0"},
      {"refine: 1\n", "refine", "expected true or false, got '1'"},
      {"refine: 'true'\n", "refine", "(quoted, so a string)"},
      {"refine: maybe\n", "refine", "expected true or false"},
      {"seed: -1\n", "seed", "expected an integer in [0, 4294967295]"},
      {"seed: 4294967296\n", "seed", "expected an integer in [0, 4294967295]"},
      {"hough: {n_theta: 7}\n", "hough.n_theta", "expected an integer in [8, 3600], got '7'"},
      {"hough: {n_theta: 3601}\n", "hough.n_theta", "in [8, 3600]"},
      {"hough: {n_theta: 180.5}\n", "hough.n_theta", "in [8, 3600]"},
      {"hough: {rho_step: 0.05}\n", "hough.rho_step", "expected a number in [0.1, 100]"},
      {"hough: {rho_step: 101}\n", "hough.rho_step", "in [0.1, 100]"},
      {"hough: {rho_step: .inf}\n", "hough.rho_step", "in [0.1, 100]"},
      {"hough: {sampling: 'random:0'}\n", "hough.sampling", sampling},
      {"hough: {sampling: every:0}\n", "hough.sampling", sampling},
      {"hough: {sampling: half}\n", "hough.sampling", sampling + " with K >= 1, got 'half'"},
      {"hough: 5\n", "hough", "expected a mapping, got '5'"},
      {"translation: {method: fft}\n", "translation.method",
       "expected one of correlation, spectra, got 'fft'"},
      {"translation: {sampling: 'random:1.5'}\n", "translation.sampling", sampling},
      {"pose_graph: {loss: l2}\n", "pose_graph.loss", "expected one of none, huber, cauchy"},
      {"pose_graph: {loss_scale: 0}\n", "pose_graph.loss_scale", "expected a number > 0"},
      {"pose_graph: {loss_scale: .inf}\n", "pose_graph.loss_scale", "a number > 0"},
      {"pose_graph: {max_edge_yaw_error_deg: 0}\n", "pose_graph.max_edge_yaw_error_deg",
       "a number > 0"},
      {"pose_graph: {max_edge_translation_error_m: -0.1}\n",
       "pose_graph.max_edge_translation_error_m", "a number > 0"},
      {"fusion: average\n", "fusion", "expected one of log_odds, max, vote, got 'average'"},
      {"name: [a, b]\n", "name", "expected a job name, got a list of 2 elements"},
      {"name: ''\n", "name", "expected a job name"},
      {"refine: true\nrefine: false\n", "refine", "appears twice (first at line 4)", 5},
  };
  for (const BadValue& c : cases) ExpectError(Minimal(c.extra), c.line, c.key, c.part);
}

// --- Rejections: structure -------------------------------------------------------------------

TEST_F(JobFileTest, CacheIsAFolderRelativeToTheJobFileWithASizeBound) {
  const std::vector<Job> jobs = Load(Minimal("cache: caches/site\ncache_max_mb: 64\n"));
  ASSERT_EQ(jobs.size(), 1u);
  EXPECT_EQ(jobs[0].options.cache_dir, dir_ / "caches" / "site");
  EXPECT_EQ(jobs[0].options.cache_max_mb, 64);
  EXPECT_EQ(Load(Minimal())[0].options.cache_max_mb, kDefaultCacheMaxMb);
  EXPECT_TRUE(Load(Minimal())[0].options.cache_dir.empty());
  ft::WriteFile(dir_ / "plain", "a file");
  ExpectError(Minimal("cache: plain\n"), 4, "cache",
              "cache folder '" + (dir_ / "plain").string() + "' exists and is not a folder");
  ExpectError(Minimal("cache_max_mb: 0\n"), 4, "cache_max_mb", "expected");
  // As --cache-max-mb without --cache: a bound on no cache is refused, not ignored, unless
  // `merge --cache` gives the job one (cli/merge_command.cpp checks it then).
  const Job bound_only = Load(Minimal("cache_max_mb: 64\n"))[0];
  EXPECT_EQ(bound_only.cache_bound_without_cache,
            (dir_ / "job.yaml").string() +
                ": line 4: key 'cache_max_mb': a size bound without a cache: give the job a "
                "'cache' folder (or run it with --cache DIR), or leave cache_max_mb out");
  EXPECT_TRUE(Load(Minimal("cache: c\ncache_max_mb: 64\n"))[0].cache_bound_without_cache.empty());
  ExpectError(Minimal("cache: [a, b]\n"), 4, "cache", "expected a cache folder");
}

TEST_F(JobFileTest, UnknownKeysAreNamedWithTheAllowedOnes) {
  ExpectError(Minimal("resolutoin: 0.05\n"), 4, "resolutoin",
              "unknown key; allowed here: name, maps, output, reference, resolution");
  ExpectError(Minimal("hough: {ntheta: 90}\n"), 4, "hough.ntheta",
              "allowed here: n_theta, rho_step, sampling");
  ExpectError(Minimal("translation: {mode: spectra}\n"), 4, "translation.mode",
              "allowed here: method, sampling");
  ExpectError(Minimal("pose_graph:\n  loss: huber\n  los: 1\n"), 6, "pose_graph.los",
              "allowed here: loss, loss_scale, max_edge_yaw_error_deg");
  ExpectError("maps:\n  - {file: maps/a.yaml}\noutput: out\n", 2, "maps[0].file",
              "allowed here: path, name");
  ExpectError("defaults: {threads: 1}\njobs:\n  - maps: [maps/a.yaml]\n    output: out\n", 1,
              "defaults", "unknown key; allowed here: jobs");
  ExpectError("jobs:\n  - maps: [maps/a.yaml]\n    output: out\n    fuse: max\n", 4, "jobs[0].fuse",
              "unknown key");
}

TEST_F(JobFileTest, MissingKeysAndEmptyLists) {
  ExpectError("output: out\nthreads: 1\n", 1, "maps",
              "missing: expected a non-empty list of map YAML files");
  ExpectError("maps: [maps/a.yaml]\n", 1, "output", "missing: expected an output folder");
  ExpectError("maps: []\noutput: out\n", 1, "maps",
              "expected a non-empty list of map YAML files, got a list of 0 elements");
  ExpectError("maps: maps/a.yaml\noutput: out\n", 1, "maps", "got 'maps/a.yaml'");
  ExpectError("maps:\n  - name: first\noutput: out\n", 2, "maps[0].path", "missing");
  ExpectError("maps:\n  - [maps/a.yaml]\noutput: out\n", 2, "maps[0]",
              "expected a map YAML or bag path, or a mapping {path, name, topic, fixed, pose, "
              "initial_pose, initial_pose_sigma}");
  ExpectError("jobs: []\n", 1, "jobs", "expected a non-empty list of jobs");
  ExpectError("jobs: 3\n", 1, "jobs", "expected a non-empty list of jobs, got '3'");
  ExpectError("jobs:\n  - maps.yaml\n", 2, "jobs[0]", "expected a job");
  ExpectError("jobs:\n  - maps: [maps/a.yaml]\n    output: out\n  - threads: 2\n", 4,
              "jobs[1].maps", "missing");
}

TEST_F(JobFileTest, MapsOfAJobAreDistinct) {
  // Same stem in two folders: named by their folders (io/map_names.hpp), never as a given name.
  const std::vector<Job> folders = Load("maps:\n  - maps/a.yaml\n  - other/a.yaml\noutput: out\n");
  ASSERT_EQ(folders.size(), 1u);
  EXPECT_EQ(folders[0].maps[0].name, "maps");
  EXPECT_EQ(folders[0].maps[1].name, "other");
  const std::vector<Job> given =
      Load("maps:\n  - maps/a.yaml\n  - {path: other/a.yaml, name: a}\noutput: out\n");
  EXPECT_EQ(given[0].maps[0].name, "maps");
  EXPECT_EQ(given[0].maps[1].name, "a");
  ExpectError(
      "maps:\n  - {path: maps/a.yaml, name: x}\n  - {path: maps/b.yaml, name: x}\n"
      "output: out\n",
      3, "maps[1].name", "map name 'x' is also the name of maps[0] (line 2)");
  ExpectError(
      "maps:\n  - maps/a.yaml\n  - {path: other/../maps/./a.yaml, name: again}\n"
      "output: out\n",
      3, "maps[1]", "'other/../maps/./a.yaml' is the same file as maps[0] (line 2)");
  ExpectError("maps: [maps/a.yaml, maps/b.yaml]\noutput: out\nreference: c\n", 3, "reference",
              "expected the name of one of the job's maps ('a', 'b'), got 'c'");
}

TEST_F(JobFileTest, FixedMapsHaveAPoseAndAreTheReference) {
  const std::vector<Job> jobs = Load(
      "maps:\n  - maps/a.yaml\n  - {path: maps/b.yaml, fixed: true, pose: [12.5, -3, 0.25]}\n"
      "  - {path: maps/c.yaml, fixed: true}\noutput: out\n");
  ASSERT_EQ(jobs.size(), 1u);
  const Job& job = jobs[0];
  ASSERT_EQ(job.maps.size(), 3u);
  EXPECT_FALSE(job.maps[0].fixed);  // default: a robot's map, which moves
  EXPECT_TRUE(job.maps[1].fixed);
  EXPECT_EQ(job.maps[1].T_merged_map.x_m(), 12.5);
  EXPECT_EQ(job.maps[1].T_merged_map.y_m(), -3.0);
  EXPECT_EQ(job.maps[1].T_merged_map.yaw_rad(), 0.25);
  EXPECT_TRUE(job.maps[2].fixed);  // default pose: identity
  EXPECT_EQ(job.maps[2].T_merged_map.x_m(), 0.0);
  EXPECT_EQ(job.maps[2].T_merged_map.y_m(), 0.0);
  EXPECT_EQ(job.maps[2].T_merged_map.yaw_rad(), 0.0);
  EXPECT_EQ(job.reference, "b");  // the first fixed map, not the first map
  // `fixed: false` is a robot's map; naming the first fixed map as the reference is fine.
  const std::vector<Job> named = Load(
      "maps:\n  - {path: maps/a.yaml, fixed: false}\n  - {path: maps/b.yaml, fixed: true}\n"
      "output: out\nreference: b\n");
  EXPECT_FALSE(named[0].maps[0].fixed);
  EXPECT_EQ(named[0].reference, "b");
}

TEST_F(JobFileTest, FixedMapErrorsNameTheKey) {
  const std::string pose = "[x, y, yaw]: a list of 3 finite numbers (m, m, rad)";
  ExpectError(
      "maps:\n  - maps/a.yaml\n  - {path: maps/b.yaml, fixed: true, pose: [1, .nan, 0]}\n"
      "output: out\n",
      3, "maps[1].pose[1]", "expected a finite number (pose is " + pose + "), got '.nan'");
  ExpectError("maps:\n  - {path: maps/a.yaml, fixed: true, pose: [.inf, 0, 0]}\noutput: out\n", 2,
              "maps[0].pose[0]", "got '.inf'");
  ExpectError("maps:\n  - {path: maps/a.yaml, fixed: true, pose: [1, 2]}\noutput: out\n", 2,
              "maps[0].pose", "expected " + pose);
  ExpectError("maps:\n  - {path: maps/a.yaml, fixed: true, pose: [1, 2, 3, 4]}\noutput: out\n", 2,
              "maps[0].pose", "expected " + pose);
  ExpectError("maps:\n  - {path: maps/a.yaml, fixed: true, pose: 1}\noutput: out\n", 2,
              "maps[0].pose", "expected " + pose + ", got '1'");
  ExpectError("maps:\n  - {path: maps/a.yaml, fixed: true, pose: [1, '2', 0]}\noutput: out\n", 2,
              "maps[0].pose[1]", "expected a finite number");
  ExpectError("maps:\n  - {path: maps/a.yaml, fixed: 1}\noutput: out\n", 2, "maps[0].fixed",
              "expected true or false, got '1'");
  ExpectError("maps:\n  - {path: maps/a.yaml, fixed: 'true'}\noutput: out\n", 2, "maps[0].fixed",
              "expected true or false");
  ExpectError("maps:\n  - {path: maps/a.yaml, pose: [0, 0, 0]}\noutput: out\n", 2, "maps[0].pose",
              "add 'fixed: true' or remove 'pose'");
  ExpectError(
      "maps:\n  - maps/a.yaml\n  - {path: maps/b.yaml, fixed: true}\noutput: out\n"
      "reference: a\n",
      5, "reference", "expected the first fixed map 'b'");
}

TEST_F(JobFileTest, MapsMayHaveAKnownStartPose) {
  const std::vector<Job> jobs = Load(
      "maps:\n  - {path: maps/a.yaml, fixed: true, pose: [1, 2, 0.5]}\n"
      "  - {path: maps/b.yaml, initial_pose: [12.5, -3, 0.25]}\n"
      "  - {path: maps/c.yaml, initial_pose: [0, 1, -3], initial_pose_sigma: [0.2, 0.05]}\n"
      "output: out\n");
  ASSERT_EQ(jobs.size(), 1u);
  const Job& job = jobs[0];
  ASSERT_EQ(job.maps.size(), 3u);
  EXPECT_FALSE(job.maps[0].prior.has_value());  // a fixed map's pose is exact
  ASSERT_TRUE(job.maps[1].prior.has_value());
  EXPECT_EQ(job.maps[1].prior->T_site_map.x_m(), 12.5);
  EXPECT_EQ(job.maps[1].prior->T_site_map.y_m(), -3.0);
  EXPECT_EQ(job.maps[1].prior->T_site_map.yaw_rad(), 0.25);
  // Default sigmas: 0.5 m and 10 deg.
  EXPECT_EQ(job.maps[1].prior->translation_sigma_m, 0.5);
  EXPECT_NEAR(job.maps[1].prior->yaw_sigma_rad, 10.0 * M_PI / 180.0, 1e-15);
  ASSERT_TRUE(job.maps[2].prior.has_value());
  EXPECT_EQ(job.maps[2].prior->translation_sigma_m, 0.2);
  EXPECT_EQ(job.maps[2].prior->yaw_sigma_rad, 0.05);
  EXPECT_EQ(job.reference, "a");
}

TEST_F(JobFileTest, PriorErrorsNameTheKey) {
  const std::string pose = "[x, y, yaw]: a list of 3 finite numbers (m, m, rad)";
  const std::string sigma =
      "[metres, radians]: a list of 2 finite numbers > 0 (the prior's translation and yaw sigma)";
  ExpectError(
      "maps:\n  - maps/a.yaml\n  - {path: maps/b.yaml, initial_pose: [1, .nan, 0]}\n"
      "output: out\n",
      3, "maps[1].initial_pose[1]",
      "expected a finite number (initial_pose is " + pose + "), got '.nan'");
  ExpectError("maps:\n  - {path: maps/a.yaml, initial_pose: [.inf, 0, 0]}\noutput: out\n", 2,
              "maps[0].initial_pose[0]", "got '.inf'");
  ExpectError("maps:\n  - {path: maps/a.yaml, initial_pose: [1, 2]}\noutput: out\n", 2,
              "maps[0].initial_pose", "expected " + pose);
  ExpectError("maps:\n  - {path: maps/a.yaml, initial_pose: 3}\noutput: out\n", 2,
              "maps[0].initial_pose", "expected " + pose + ", got '3'");
  ExpectError(
      "maps:\n  - {path: maps/a.yaml, initial_pose: [0, 0, 0], initial_pose_sigma: [-0.5, 0.1]}\n"
      "output: out\n",
      2, "maps[0].initial_pose_sigma[0]",
      "expected a finite number > 0 (initial_pose_sigma is " + sigma + "), got '-0.5'");
  ExpectError(
      "maps:\n  - {path: maps/a.yaml, initial_pose: [0, 0, 0], initial_pose_sigma: [0.5, 0]}\n"
      "output: out\n",
      2, "maps[0].initial_pose_sigma[1]", "expected a finite number > 0");
  ExpectError(
      "maps:\n  - {path: maps/a.yaml, initial_pose: [0, 0, 0], initial_pose_sigma: [0.5, .nan]}"
      "\noutput: out\n",
      2, "maps[0].initial_pose_sigma[1]", "got '.nan'");
  ExpectError(
      "maps:\n  - {path: maps/a.yaml, initial_pose: [0, 0, 0], initial_pose_sigma: [0.5]}\n"
      "output: out\n",
      2, "maps[0].initial_pose_sigma", "expected " + sigma);
  ExpectError(
      "maps:\n  - {path: maps/a.yaml, initial_pose: [0, 0, 0], initial_pose_sigma: 0.5}\n"
      "output: out\n",
      2, "maps[0].initial_pose_sigma", "expected " + sigma + ", got '0.5'");
  ExpectError("maps:\n  - {path: maps/a.yaml, initial_pose_sigma: [0.5, 0.1]}\noutput: out\n", 2,
              "maps[0].initial_pose_sigma", "add 'initial_pose: [x, y, yaw]'");
  ExpectError("maps:\n  - {path: maps/a.yaml, fixed: true, initial_pose: [0, 0, 0]}\noutput: out\n",
              2, "maps[0].initial_pose", "a fixed map's pose is its 'pose', exactly");
  // Radians, not degrees: a quarter turn written as 90, ten degrees of sigma written as 10.
  ExpectError("maps:\n  - {path: maps/a.yaml, initial_pose: [1, 2, 90]}\noutput: out\n", 2,
              "maps[0].initial_pose[2]",
              "expected a yaw in radians, at most 2 pi in magnitude: 90 rad looks like degrees "
              "(90 deg is 1.5708 rad), got '90'");
  ExpectError("maps:\n  - {path: maps/a.yaml, fixed: true, pose: [1, 2, -180]}\noutput: out\n", 2,
              "maps[0].pose[2]", "-180 rad looks like degrees");
  ExpectError(
      "maps:\n  - {path: maps/a.yaml, initial_pose: [0, 0, 0], initial_pose_sigma: [0.5, 10]}\n"
      "output: out\n",
      2, "maps[0].initial_pose_sigma[1]",
      "expected a yaw sigma in radians, at most pi: 10 rad looks like degrees");
  ExpectError(
      "maps:\n  - {path: maps/a.yaml, fixed: true, initial_pose_sigma: [0.5, 0.1]}\noutput: out\n",
      2, "maps[0].initial_pose_sigma", "a fixed map's pose is exact: remove 'initial_pose_sigma'");
  ExpectError("maps:\n  - {path: maps/a.yaml, initial_pos: [0, 0, 0]}\noutput: out\n", 2,
              "maps[0].initial_pos", "allowed here: path, name, topic, fixed, pose, initial_pose");
}

TEST_F(JobFileTest, JobsHaveTheirOwnOutputAndName) {
  ExpectError(
      "jobs:\n  - maps: [maps/a.yaml]\n    output: out\n"
      "  - maps: [maps/b.yaml]\n    output: ./out/\n",
      5, "jobs[1].output", "is also the output folder of job 'job 1' (line 2)");
  ExpectError(
      "jobs:\n  - {name: x, maps: [maps/a.yaml], output: out/1}\n"
      "  - {name: x, maps: [maps/b.yaml], output: out/2}\n",
      3, "jobs[1].name", "job name 'x' is also the name of job 'x' (line 2)");
  ft::WriteFile(dir_ / "taken", "a file");
  ExpectError("maps: [maps/a.yaml]\noutput: taken\n", 2, "output", "exists and is not a folder");
}

TEST_F(JobFileTest, BadMapFilesStopTheWholeFile) {
  ft::WriteFile(dir_ / "maps" / "broken.yaml",
                "image: tiny.pgm\nresolution: -1\norigin: [0,0,0]\n");
  const std::string text =
      "jobs:\n  - {maps: [maps/a.yaml], output: out/1}\n"
      "  - maps:\n      - maps/b.yaml\n      - maps/missing.yaml\n    output: out/2\n";
  ExpectError(text, 5, "jobs[1].maps[1]", "missing.yaml: cannot open map YAML file");
  ExpectError("maps: [maps/a.yaml, maps/broken.yaml]\noutput: out\n", 1, "maps[1]",
              "broken.yaml: line 2: key 'resolution': expected a number > 0");
}

TEST_F(JobFileTest, TheFileItself) {
  const fs::path job = dir_ / "job.yaml";
  EXPECT_TRUE(StartsWith(LoadError("maps: [a\noutput: out\n"), job.string() + ": line "));
  EXPECT_TRUE(Contains(LoadError("maps: [a\noutput: out\n"), "malformed YAML"));
  EXPECT_EQ(LoadError(""), job.string() +
                               ": expected a job (a mapping with 'maps' and 'output') or 'jobs:' "
                               "with a list of jobs, got an empty value");
  EXPECT_TRUE(Contains(LoadError("- maps/a.yaml\n"), "got a list of 1 element"));
  try {
    LoadJobFile(dir_ / "nope.yaml");
    ADD_FAILURE() << "no error for a missing job file";
  } catch (const fleetmerge::Error& e) {
    EXPECT_TRUE(StartsWith(e.what(), (dir_ / "nope.yaml").string() + ": cannot open job file"));
  }
}

// --- The examples in configs/ ------------------------------------------------------------------

fs::path ConfigsDir() { return fs::path(FLEETMERGE_SOURCE_DIR) / "configs"; }

TEST(JobFileConfigsTest, ExamplesLoad) {
  const fs::path maps = ConfigsDir() / "../../shared/data/maps";
  if (!fs::is_directory(maps)) {
    GTEST_SKIP() << "SKIPPED: the examples name maps in " << maps << ", which is absent";
  }
  const std::vector<Job> four = LoadJobFile(ConfigsDir() / "four_robots.yaml");
  ASSERT_EQ(four.size(), 1u);
  EXPECT_EQ(four[0].maps.size(), 4u);

  const std::vector<Job> large = LoadJobFile(ConfigsDir() / "large_fleet.yaml");
  ASSERT_GE(large.size(), 2u);
  EXPECT_GE(large[0].maps.size(), 6u);

  const std::vector<Job> mixed = LoadJobFile(ConfigsDir() / "mixed_resolutions.yaml");
  ASSERT_FALSE(mixed.empty());
  EXPECT_EQ(mixed[0].options.resolution_m, 0.05);

  const std::vector<Job> fixed = LoadJobFile(ConfigsDir() / "fixed_base.yaml");
  ASSERT_EQ(fixed.size(), 1u);
  ASSERT_EQ(fixed[0].maps.size(), 4u);
  EXPECT_TRUE(fixed[0].maps[0].fixed);
  EXPECT_EQ(fixed[0].maps[0].T_merged_map.x_m(), 10.0);
  EXPECT_EQ(fixed[0].reference, "site");

  const std::vector<Job> priors = LoadJobFile(ConfigsDir() / "site_with_priors.yaml");
  ASSERT_EQ(priors.size(), 1u);
  ASSERT_EQ(priors[0].maps.size(), 4u);
  EXPECT_TRUE(priors[0].maps[0].fixed);
  for (std::size_t m = 1; m < 4; ++m) EXPECT_TRUE(priors[0].maps[m].prior.has_value()) << m;

  for (const auto& jobs : {four, large, mixed, fixed, priors}) {
    for (const Job& job : jobs) {  // under the repository's (git-ignored) out/ folder
      EXPECT_EQ(job.output_dir.lexically_normal().parent_path(),
                (fs::path(FLEETMERGE_SOURCE_DIR) / "out").lexically_normal())
          << job.name;
    }
  }
}

TEST(JobFileConfigsTest, ReadmeDocumentsEveryKey) {
  const std::string readme = ft::ReadFile(ConfigsDir() / "README.md");
  for (const char* key : {"name",
                          "maps",
                          "path",
                          "output",
                          "reference",
                          "resolution",
                          "threads",
                          "hypotheses_per_pair",
                          "omega_threshold",
                          "min_overlap_cells",
                          "refine",
                          "seed",
                          "hough",
                          "n_theta",
                          "rho_step",
                          "sampling",
                          "translation",
                          "method",
                          "pose_graph",
                          "loss",
                          "loss_scale",
                          "max_edge_yaw_error_deg",
                          "max_edge_translation_error_m",
                          "fusion",
                          "jobs",
                          "four_robots.yaml",
                          "large_fleet.yaml",
                          "mixed_resolutions.yaml",
                          "fixed",
                          "pose",
                          "fixed_base.yaml",
                          "initial_pose",
                          "initial_pose_sigma",
                          "site_with_priors.yaml"}) {
    EXPECT_TRUE(Contains(readme, std::string("`") + key)) << key;
  }
}

}  // namespace
}  // namespace fleetmerge
