#include "pipeline/fleet_merge.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <map>
#include <optional>
#include <sstream>
#include <tuple>

#include "core/acceptance_index.hpp"
#include "core/error.hpp"
#include "core/hypothesis_generator.hpp"
#include "core/parallel.hpp"
#include "core/resample.hpp"
#include "pipeline/composite.hpp"
#include "pipeline/corroboration.hpp"
#include "pipeline/fleet_graph.hpp"
#include "pipeline/map_label.hpp"
#include "pipeline/pair_cache.hpp"
#include "pipeline/pose_priors.hpp"
#include "pipeline/preview.hpp"
#include "pipeline/weak_bridges.hpp"

namespace fleetmerge {
namespace {

std::vector<OccupancyGrid> AtOneResolution(const std::vector<const OccupancyGrid*>& maps,
                                           double resolution_m, std::int64_t max_cells) {
  // A map of absurd resolution (1e-9 m beside 0.05 m) would be resampled to an absurd size:
  // refused with the same cell limit as the images, computed in double before any cast.
  for (std::size_t m = 0; m < maps.size(); ++m) {
    const double ratio = maps[m]->geometry().resolution_m() / resolution_m;
    const double width = std::ceil(maps[m]->width() * ratio);
    const double height = std::ceil(maps[m]->height() * ratio);
    if (!(width * height <= static_cast<double>(max_cells))) {
      std::ostringstream what;
      what << "map " << m + 1 << " (in job order), " << maps[m]->width() << " x "
           << maps[m]->height() << " cells of " << maps[m]->geometry().resolution_m()
           << " m, would be " << width << " x " << height << " cells at the job's resolution "
           << resolution_m << " m, more than the limit of " << max_cells
           << " cells (check the maps' resolutions, or raise max_map_cells)";
      throw Error(what.str());
    }
  }
  std::vector<OccupancyGrid> out;
  out.reserve(maps.size());
  // A map already at resolution_m shares its cells (OccupancyGrid copies share them; nothing in
  // a merge writes to an input): copying them took 33 ACES maps ~25 ms of one thread.
  for (const OccupancyGrid* m : maps) {
    out.push_back(
        HasResolution(m->geometry(), resolution_m) ? *m : ResampleToResolution(*m, resolution_m));
  }
  return out;
}

void AcceptByThreshold(std::vector<PairOutcome>& pairs, const FleetOptions& options) {
  for (PairOutcome& p : pairs) {
    // A pair the priors refused keeps its hypotheses: its best is judged all the same.
    p.accepted = p.best_omega() >= options.omega_threshold &&
                 p.overlap_cells >= options.min_overlap_cells &&
                 p.wall_agreement >= options.min_wall_agreement;
    if (p.accepted && p.refused_by_priors) {
      p.accepted = false;  // the priors decided: its note says which ones it contradicts
      p.note = "refused: " + p.note;
    } else if (!p.accepted) {
      const std::string reason =
          p.hypotheses.empty()                       ? "no hypothesis (a map has no occupied cell)"
          : p.best_omega() < options.omega_threshold ? "best omega below the threshold"
          : p.overlap_cells < options.min_overlap_cells ? "overlap below min_overlap_cells"
                                                        : "wall agreement below min_wall_agreement";
      // The priors' note (hypotheses they dropped, or all contradicted) stays after the reason:
      // a pair that fails the thresholds anyway was not refused by the priors.
      p.note =
          p.note.empty() ? reason : reason + (p.refused_by_priors ? "; also, " : "; ") + p.note;
      p.refused_by_priors = false;
    }
    p.edge_hypothesis = p.accepted ? 0 : -1;
  }
}

// Rejects every accepted edge across `split`: the maps on its two sides that overlap under the
// solved poses contradict each other (pipeline/corroboration.hpp). Returns whether it cut any:
// maps tied by their known poses (fixed, or priors) have no edge between them to cut.
bool CutSplit(const ComponentSplit& split, std::vector<PairOutcome>& pairs,
              const std::vector<std::string>& map_names) {
  bool cut = false;
  const std::string names = MapList(map_names, split.detached);
  const auto detached = [&](int m) {
    return std::find(split.detached.begin(), split.detached.end(), m) != split.detached.end();
  };
  for (PairOutcome& p : pairs) {
    if (!p.accepted || detached(p.a) == detached(p.b)) continue;
    p.accepted = false;
    p.edge_hypothesis = -1;
    p.note = "rejected: the placement of map(s) " + names + " is contradicted by " +
             std::to_string(split.conflicts) + " of the pairs that then overlap (on " +
             std::to_string(split.conflict_cells) + " cells), supported by " +
             std::to_string(split.supporters) + " (on " + std::to_string(split.supporter_cells) +
             " cells)";
    cut = true;
  }
  return cut;
}

// Rejects a bridge edge whose walls are below the lone-link standard (pipeline/weak_bridges.hpp).
void RejectWeakBridge(double min_bridge_wall_agreement, PairOutcome& pair) {
  std::ostringstream note;
  note << "rejected: the only link between two groups of maps, which no cycle checks, and ";
  if (pair.edge_hypothesis == 0) {
    note << "its wall agreement " << pair.wall_agreement;
  } else {
    note << "its hypothesis " << pair.edge_hypothesis + 1 << " has no measured wall agreement";
  }
  note << " is below min_bridge_wall_agreement " << min_bridge_wall_agreement;
  pair.accepted = false;
  pair.edge_hypothesis = -1;
  pair.note = note.str();
}

// Rejects an ambiguous edge that no cycle or other pair confirms (pipeline/weak_bridges.hpp).
void RejectUnconfirmedAmbiguous(PairOutcome& pair) {
  std::ostringstream note;
  note << "rejected: ambiguous (hypothesis 2 is a different pose with nearly the same evidence, "
          "margin "
       << pair.margin_nats << " nats) and no cycle or other pair confirms hypothesis 1";
  pair.accepted = false;
  pair.edge_hypothesis = -1;
  pair.note = note.str();
}

// The merged map's cell size: the job's `resolution`, else the component's reference map's.
double MergedResolution(const std::vector<const OccupancyGrid*>& maps,
                        const FleetComponent& component, const FleetOptions& options) {
  return options.resolution_m > 0.0 ? options.resolution_m
                                    : maps[component.reference]->geometry().resolution_m();
}

// Whether merged cells of resolution_m are the cells the pairs compared (result.maps), or need
// the original maps resampled.
bool ComparedCells(double resolution_m, const FleetResult& result) {
  return std::abs(resolution_m - result.resolution_m) <= 1e-9 * resolution_m;
}

// A component of one map as its merged map: the map's cells as they are (compositing would crop
// them to the known ones) on its lattice moved by its pose in the merged frame, so that the map
// file lies where the report and the launch files put the map.
void PlaceAsItIs(const std::vector<const OccupancyGrid*>& maps, const FleetResult& result,
                 FleetComponent& component, const FleetOptions& options) {
  const int m = component.maps.front();
  const double resolution_m = MergedResolution(maps, component, options);
  const bool compared_cells = ComparedCells(resolution_m, result);
  const OccupancyGrid grid =
      compared_cells ? result.maps[m] : ResampleToResolution(*maps[m], resolution_m);
  const GridGeometry& g = grid.geometry();
  component.merged.emplace(
      GridGeometry(g.resolution_m(), g.size(), result.T_component_map[m] * g.T_map_grid()),
      grid.cells());
}

// The component's merged map, on its reference map's cells: at the job's resolution when the
// job sets one, else at the reference's own. Users navigate in the reference robot's map, so
// where only that map knows a cell the merged map holds that very cell; a fixed (base) map is
// the reference, and every cell it knows is kept (Composite's fixed inputs). Inputs finer than
// the merged cells are coarsened from the original maps first (ResampleToResolution keeps
// one-cell walls that a nearest-cell lookup would drop).
void CompositeComponent(const std::vector<const OccupancyGrid*>& maps, const FleetResult& result,
                        const FixedPoses& fixed, FleetComponent& component,
                        const FleetOptions& options) {
  const double resolution_m = MergedResolution(maps, component, options);
  const bool compared_cells = ComparedCells(resolution_m, result);
  std::vector<OccupancyGrid> resampled;  // only when the merged cells are not the compared ones
  resampled.reserve(component.maps.size());
  std::vector<CompositeInput> inputs;
  int reference_input = -1;
  for (const int m : component.maps) {
    if (m == component.reference) reference_input = static_cast<int>(inputs.size());
    const OccupancyGrid* grid = &result.maps[m];
    if (!compared_cells) {
      resampled.push_back(ResampleToResolution(*maps[m], resolution_m));
      grid = &resampled.back();
    }
    inputs.push_back({grid, result.T_component_map[m], IsFixed(fixed, m)});
  }
  std::optional<PreviewColourer> preview;
  if (options.previews && compared_cells) preview.emplace();
  try {
    component.merged =
        Composite(inputs, resolution_m, options.fusion, options.threads, reference_input,
                  preview ? &*preview : nullptr, options.max_map_cells);
  } catch (const Error& e) {
    throw Error("compositing maps " + MapList(options.map_names, component.maps) +
                JobOrderNote(options.map_names) + ": " + e.what());
  }
  if (preview) component.preview = preview->image();
}

// Where the pose graph measures the edge of b's pose in a's frame T_a_b: the centre of b's known
// cells on a's known cells (b's frame, metres), or b's frame origin when none overlap. Every 8th
// row and column of b: a centre a few cells off changes nothing against lever arms of metres,
// and the 339 accepted pairs of scripts/cache_rerun_benchmark.sh's 33 robots take ~10 ms of the
// refine stage this way, ~400 ms at every 2nd.
Eigen::Vector2d OverlapAnchor(const OccupancyGrid& a, const OccupancyGrid& b, const Pose2& T_a_b) {
  const Pose2 T_ga_gb = CellPoseFromMapPose(a.geometry(), b.geometry(), T_a_b);
  const std::optional<Eigen::Vector2d> centre_cells = OverlapCentre(a, b, T_ga_gb, 8);
  if (!centre_cells) return Eigen::Vector2d::Zero();
  return b.geometry().T_map_grid() * (*centre_cells * b.geometry().resolution_m());
}

}  // namespace

FleetResult MergeFleet(const std::vector<const OccupancyGrid*>& maps, int reference,
                       const FleetOptions& options, const ProgressFn& progress, PairCache* cache) {
  return MergeFleet(maps, reference, FixedPoses{}, options, progress, cache);
}

namespace {

void CheckFixed(const FixedPoses& fixed, std::size_t map_count, int reference,
                const std::vector<std::string>& names) {
  if (fixed.empty()) return;
  if (fixed.size() != map_count) {
    throw Error("fixed map poses: " + std::to_string(fixed.size()) + " given for " +
                std::to_string(map_count) + " maps (one per map, or none)");
  }
  int first = -1;
  for (std::size_t m = 0; m < fixed.size(); ++m) {
    if (!fixed[m]) continue;
    if (first < 0) first = static_cast<int>(m);
    const Pose2& T = *fixed[m];
    if (!std::isfinite(T.x_m()) || !std::isfinite(T.y_m()) || !std::isfinite(T.yaw_rad())) {
      std::ostringstream what;
      what << MapLabel(names, static_cast<int>(m)) << JobOrderNote(names)
           << " is fixed with a non-finite pose [" << T.x_m() << ", " << T.y_m() << ", "
           << T.yaw_rad() << "]; expected finite [x, y, yaw]";
      throw Error(what.str());
    }
  }
  if (first >= 0 && reference != first) {
    throw Error("with fixed maps the reference must be the first fixed map (" +
                MapLabel(names, first) + JobOrderNote(names) + "), not " +
                MapLabel(names, reference));
  }
}

}  // namespace

FleetResult MergeFleet(const std::vector<const OccupancyGrid*>& maps, int reference,
                       const FixedPoses& fixed, const FleetOptions& options,
                       const ProgressFn& progress, PairCache* cache) {
  return MergeFleet(maps, reference, fixed, PosePriors{}, options, progress, cache);
}

FleetResult MergeFleet(const std::vector<const OccupancyGrid*>& maps, int reference,
                       const FixedPoses& fixed, const PosePriors& priors,
                       const FleetOptions& options, const ProgressFn& progress, PairCache* cache) {
  if (maps.empty()) throw Error("a fleet-merging job needs at least one map");
  if (reference < 0 || reference >= static_cast<int>(maps.size())) {
    throw Error("the reference map index is out of range");
  }
  if (!options.map_names.empty() && options.map_names.size() != maps.size()) {
    throw Error("map names: " + std::to_string(options.map_names.size()) + " given for " +
                std::to_string(maps.size()) + " maps (one per map, or none)");
  }
  CheckFixed(fixed, maps.size(), reference, options.map_names);
  CheckPriors(priors, fixed, maps.size(), options.map_names);
  FleetResult result;
  result.resolution_m = options.resolution_m;
  if (!(result.resolution_m > 0.0)) {  // default: the finest of the maps
    result.resolution_m = maps.front()->geometry().resolution_m();
    for (const auto* m : maps) {
      result.resolution_m = std::min(result.resolution_m, m->geometry().resolution_m());
    }
  }
  result.maps = AtOneResolution(maps, result.resolution_m, options.max_map_cells);

  auto start = std::chrono::steady_clock::now();
  // Hypotheses are ranked with the overlap an edge needs (HypothesisOptions::min_overlap_cells).
  PairOptions pair_options = options.pair;
  pair_options.hypotheses.min_overlap_cells = options.min_overlap_cells;
  std::vector<char> fixed_maps;  // empty: none fixed
  for (std::size_t m = 0; m < fixed.size(); ++m) fixed_maps.push_back(fixed[m] ? 1 : 0);
  std::optional<FixedMapPairs> fixed_map_pairs;
  if (!fixed_maps.empty()) {
    fixed_map_pairs.emplace(FixedMapPairs{fixed_maps, pair_options});
    fixed_map_pairs->options.hypotheses.translation.free_penalty = options.fixed_map_free_penalty;
  }
  // Each map's walls, for the judging below: the pair search hands on those of the maps it
  // prepared.
  std::vector<std::optional<MapWalls>> map_walls;
  result.pairs = ComputeAllPairs(result.maps, pair_options, options.threads, progress, cache,
                                 fixed_map_pairs ? &*fixed_map_pairs : nullptr, &map_walls);
  if (cache) cache->Close();  // trimmed and released: another job may use it while this one goes on
  result.timing.pairs_ms = MillisecondsSince(start);

  start = std::chrono::steady_clock::now();
  DropHypothesesAgainstPriors(result.pairs, fixed, priors, options.map_names);
  AcceptByThreshold(result.pairs, options);
  // Each edge measured where its two maps overlap (refine/pose_graph.hpp, anchor_b_m), made once
  // per pair and hypothesis: the accepted pairs' in parallel here, a hypothesis that replaces
  // one (pipeline/fleet_graph.hpp's cycle checks) when it is first asked for.
  std::map<std::tuple<int, int, int>, Eigen::Vector2d> anchors_m;
  {
    std::vector<const PairOutcome*> accepted;
    for (const PairOutcome& pair : result.pairs) {
      if (pair.accepted) accepted.push_back(&pair);
    }
    std::vector<Eigen::Vector2d> made(accepted.size());
    ParallelFor(accepted.size(), options.threads, [&](std::size_t k) {
      const PairOutcome& pair = *accepted[k];
      made[k] = OverlapAnchor(result.maps[pair.a], result.maps[pair.b],
                              pair.hypotheses[pair.edge_hypothesis].T_a_b);
    });
    for (std::size_t k = 0; k < accepted.size(); ++k) {
      anchors_m[{accepted[k]->a, accepted[k]->b, accepted[k]->edge_hypothesis}] = made[k];
    }
  }
  const EdgeAnchor anchor = [&](const PairOutcome& pair, int h) {
    auto [at, made] = anchors_m.try_emplace({pair.a, pair.b, h}, Eigen::Vector2d::Zero());
    if (made) {
      at->second =
          OverlapAnchor(result.maps[pair.a], result.maps[pair.b], pair.hypotheses[h].T_a_b);
    }
    return at->second;
  };
  FleetGraph graph =
      SolveFleetGraph(static_cast<int>(maps.size()), result.pairs, reference, options.pose_graph,
                      fixed, priors, anchor, options.min_bridge_wall_agreement);
  // Made once, in parallel (but for those the pair search handed on): every round judges the
  // pairs again.
  ParallelFor(map_walls.size(), options.threads, [&](std::size_t m) {
    if (!map_walls[m]) map_walls[m].emplace(result.maps[m]);
  });
  std::vector<MapWalls> walls;
  walls.reserve(map_walls.size());
  for (auto& w : map_walls) walls.push_back(std::move(*w));
  // Each round rejects at least one edge, so this ends.
  for (std::size_t round = 0; round <= result.pairs.size(); ++round) {
    if (const auto weak = WeakestBridge(static_cast<int>(maps.size()), result.pairs,
                                        options.min_bridge_wall_agreement, fixed_maps)) {
      RejectWeakBridge(options.min_bridge_wall_agreement, result.pairs[*weak]);
    } else {
      const auto verdicts =
          JudgeSolvedPairs(result.maps, walls, result.pairs, graph, options.min_overlap_cells,
                           options.min_wall_agreement, options.pose_graph, options.threads);
      if (const auto ambiguous =
              UnconfirmedAmbiguousEdge(static_cast<int>(maps.size()), result.pairs, verdicts)) {
        RejectUnconfirmedAmbiguous(result.pairs[*ambiguous]);
      } else {
        const auto split = MostContradictedSplit(verdicts, graph.component_of);
        if (!split || !CutSplit(*split, result.pairs, options.map_names)) break;
      }
    }
    graph =
        SolveFleetGraph(static_cast<int>(maps.size()), result.pairs, reference, options.pose_graph,
                        fixed, priors, anchor, options.min_bridge_wall_agreement);
  }
  result.component_of = graph.component_of;
  result.T_component_map = graph.T_component_map;
  result.placed_by = graph.placed_by;
  result.timing.refine_ms = MillisecondsSince(start);
  if (progress) progress("refine", 1, 1);

  start = std::chrono::steady_clock::now();
  result.components.resize(graph.component_reference.size());
  for (std::size_t c = 0; c < result.components.size(); ++c) {
    FleetComponent& component = result.components[c];
    component.reference = graph.component_reference[c];
    for (int m = 0; m < static_cast<int>(maps.size()); ++m) {
      if (graph.component_of[m] == static_cast<int>(c)) component.maps.push_back(m);
    }
    if (component.maps.size() == 1 &&
        (maps.size() == 1 || result.placed_by[component.maps[0]] != PlacedBy::kUnmerged)) {
      // A one-map job (even all unknown, or 1 x 1 cell), and a fixed map or a map with a prior
      // that no other map joined: its pose in the site frame is known, and a site's daily job
      // still writes the site's map. Other components of one map get none: the map file is its
      // own result.
      PlaceAsItIs(maps, result, component, options);
    } else if (component.maps.size() >= 2) {
      CompositeComponent(maps, result, fixed, component, options);
    }
    if (progress) progress("composite", static_cast<int>(c) + 1, int(result.components.size()));
  }
  result.timing.composite_ms = MillisecondsSince(start);
  return result;
}

}  // namespace fleetmerge
