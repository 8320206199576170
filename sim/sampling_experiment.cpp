#include "sim/sampling_experiment.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>
#include <sstream>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "pipeline/pair_merge.hpp"
#include "sim/ground_truth_pair.hpp"

namespace fleetmerge {
namespace {

// One problem: map a re-framed (a_new), map b as it is, and the truth T_anew_b.
struct Problem {
  int a = 0, b = 0;
  OccupancyGrid a_new;
  Pose2 T_anew_b;
};

std::vector<Problem> MakeProblems(const GroundTruth& truth,
                                  const std::vector<const OccupancyGrid*>& grids,
                                  const SamplingExperimentOptions& options) {
  std::vector<std::pair<int, int>> pairs;
  auto index = [&](const std::string& name) {
    for (std::size_t i = 0; i < truth.maps.size(); ++i) {
      if (truth.maps[i].name == name) return static_cast<int>(i);
    }
    throw Error("overlap names an unknown map '" + name + "'");
  };
  for (const TruthOverlap& o : truth.overlaps) {
    if (o.cells >= options.min_overlap_cells) pairs.emplace_back(index(o.a), index(o.b));
  }
  if (pairs.empty()) {
    throw Error("no pair of maps overlaps by at least " +
                std::to_string(options.min_overlap_cells) + " cells in the truth");
  }
  std::mt19937 rng(options.seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Problem> problems;
  for (int t = 0; t < options.trials; ++t) {
    auto [a, b] = pairs[std::uniform_int_distribution<std::size_t>(0, pairs.size() - 1)(rng)];
    if (unit(rng) < 0.5) std::swap(a, b);  // either map may be the one moved
    const Pose2 T_a_anew((unit(rng) * 2 - 1) * options.max_offset_m,
                         (unit(rng) * 2 - 1) * options.max_offset_m, (unit(rng) * 2 - 1) * M_PI);
    const Pose2 T_a_b = truth.maps[a].T_building_map.inverse() * truth.maps[b].T_building_map;
    problems.push_back({a, b, Reframe(*grids[a], T_a_anew), T_a_anew.inverse() * T_a_b});
  }
  return problems;
}

SamplingOptions ToSampling(const SamplingSetting& s, std::uint32_t seed) {
  SamplingOptions o;
  o.mode = s.mode;
  o.fraction = s.fraction;
  o.step = s.step;
  o.seed = seed;
  return o;
}

// The upper median (the middle value of an even count rounded up).
double UpperMedian(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

}  // namespace

PairOptions SamplingExperimentOptions::PaperPairOptions() {
  PairOptions pair;
  pair.refine = false;
  pair.hypotheses.translation.method = TranslationMethod::kXySpectra;
  return pair;
}

std::string SamplingSetting::Label() const {
  std::ostringstream s;
  if (mode == SamplingMode::kEveryKth) {
    s << "every:" << step;
  } else if (mode == SamplingMode::kRandomFraction) {
    s << "random:" << fraction;
  } else {
    s << "all";
  }
  return s.str();
}

std::vector<SamplingSetting> PaperSamplingSettings() {
  std::vector<SamplingSetting> settings;
  for (int percent = 5; percent <= 100; percent += 5) {
    settings.push_back({SamplingMode::kRandomFraction, percent / 100.0, 1});
  }
  for (int k = 1; k <= 20; ++k) settings.push_back({SamplingMode::kEveryKth, 1.0, k});
  return settings;
}

std::vector<SamplingTrial> RunSamplingExperiment(const GroundTruth& truth,
                                                 const std::vector<const OccupancyGrid*>& grids,
                                                 const std::vector<SamplingSetting>& settings,
                                                 const SamplingExperimentOptions& options,
                                                 const SamplingProgressFn& progress) {
  const std::vector<Problem> problems = MakeProblems(truth, grids, options);
  const std::size_t n_trials = problems.size();
  std::vector<SamplingTrial> rows(settings.size() * n_trials);
  const int total = static_cast<int>(rows.size());
  int done = 0;
  // Trials outer, settings inner: a burst of load from other processes then slows all settings
  // of a trial alike instead of a run of settings (the machine may be shared).
  for (std::size_t t = 0; t < n_trials; ++t) {
    const Problem& p = problems[t];
    for (std::size_t s = 0; s < settings.size(); ++s) {
      // The trial's own seeds, so that every setting samples the same way on the same problem.
      PairOptions pair = options.pair;
      pair.hypotheses.hough_sampling = ToSampling(settings[s], 2 * t + 1);
      pair.hypotheses.spectra_sampling = ToSampling(settings[s], 2 * t + 2);
      const auto start = std::chrono::steady_clock::now();
      const PairResult result = MergePair(p.a_new, *grids[p.b], pair);
      SamplingTrial& row = rows[s * n_trials + t];
      row.time_ms = MillisecondsSince(start);
      row.setting = static_cast<int>(s);
      row.trial = static_cast<int>(t);
      row.a = truth.maps[p.a].name;
      row.b = truth.maps[p.b].name;
      if (!result.hypotheses.empty()) {
        const PairHypothesis& best = result.hypotheses.front();
        row.best_omega = best.omega;
        const PoseError error = ComparePoses(*grids[p.b], best.T_a_b, p.T_anew_b);
        row.yaw_error_deg = error.yaw_deg;
        row.displacement_cells = error.mean_displacement_cells;
        row.coarse = error.yaw_deg <= 1.0 && error.mean_displacement_cells <= 3.0;
      }
      if (progress) progress(++done, total);
    }
  }
  return rows;
}

std::vector<SamplingSummary> SummarizeSampling(const std::vector<SamplingSetting>& settings,
                                               const std::vector<SamplingTrial>& trials) {
  std::vector<SamplingSummary> out;
  for (std::size_t s = 0; s < settings.size(); ++s) {
    SamplingSummary sum;
    sum.setting = settings[s];
    std::vector<double> displacement, times;
    int n = 0, success = 0;
    sum.min_omega = 1.0;
    for (const SamplingTrial& t : trials) {
      if (t.setting != static_cast<int>(s)) continue;
      ++n;
      sum.mean_time_ms += t.time_ms;
      sum.mean_omega += t.best_omega;
      sum.min_omega = std::min(sum.min_omega, t.best_omega);
      sum.max_omega = std::max(sum.max_omega, t.best_omega);
      success += t.coarse;
      displacement.push_back(t.displacement_cells);
      times.push_back(t.time_ms);
    }
    if (n > 0) {
      sum.mean_time_ms /= n;
      sum.mean_omega /= n;
      sum.success_rate = double(success) / n;
      sum.median_displacement_cells = UpperMedian(displacement);
      sum.median_time_ms = UpperMedian(times);
    }
    out.push_back(sum);
  }
  return out;
}

}  // namespace fleetmerge
