#include "pipeline/octree_maps.hpp"

#include <octomap/OcTree.h>

#include <algorithm>
#include <chrono>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "io/octree_io.hpp"
#include "octree/octree_merge.hpp"
#include "octree/octree_projection.hpp"
#include "pipeline/placed_by.hpp"

namespace fleetmerge {
namespace {

// The map whose floor is the component's z = 0: its reference if an octree, else its first
// octree; -1 when the component has none.
int VerticalReference(const FleetComponent& component, const std::vector<JobOctree>& octrees) {
  if (octrees[component.reference].tree) return component.reference;
  for (int m : component.maps) {
    if (octrees[m].tree) return m;
  }
  return -1;
}

}  // namespace

LoadedMap LoadOctreeMap(const std::filesystem::path& path, const OctreeOptions& options,
                        JobOctree& octree) {
  std::shared_ptr<const octomap::OcTree> tree = LoadOctree(path);
  const auto start = std::chrono::steady_clock::now();
  OctreeFloorPlan plan;
  try {
    plan = ProjectOctree(*tree, options);
  } catch (const Error& e) {
    throw Error(path.string() + ": " + e.what());
  }
  octree.projection_ms = MillisecondsSince(start);
  octree.tree = std::move(tree);
  octree.floor_z_m = plan.floor_z_m;
  LoadedMap loaded;
  loaded.grid = std::move(plan.grid);
  loaded.metadata.yaml_path = path;
  loaded.metadata.image_path = path;
  loaded.metadata.resolution_m = loaded.grid.geometry().resolution_m();
  loaded.metadata.origin = loaded.grid.geometry().T_map_grid();
  return loaded;
}

std::vector<std::optional<double>> VerticalOffsets(const FleetResult& result,
                                                   const std::vector<JobOctree>& octrees) {
  std::vector<std::optional<double>> z_m(octrees.size());
  for (const FleetComponent& component : result.components) {
    const int vertical_reference = VerticalReference(component, octrees);
    if (vertical_reference < 0) continue;
    for (int m : component.maps) {
      // The floors coincide: floor_ref = floor_m + z_m (the reference's own z is 0).
      if (octrees[m].tree) z_m[m] = octrees[vertical_reference].floor_z_m - octrees[m].floor_z_m;
    }
  }
  return z_m;
}

OctreeOutputs WriteMergedOctrees(const FleetResult& result, const std::vector<JobOctree>& octrees,
                                 const std::filesystem::path& dir,
                                 const std::vector<std::filesystem::path>& protect,
                                 AtomicWrite mode) {
  const auto start = std::chrono::steady_clock::now();
  OctreeOutputs out;
  out.z_m = VerticalOffsets(result, octrees);
  out.merged_files.resize(result.components.size());
  for (std::size_t c = 0; c < result.components.size(); ++c) {
    const FleetComponent& component = result.components[c];
    if (!component.merged) continue;  // an unmerged map: its octree is its own result
    std::vector<OctreeInput> inputs;
    double resolution_m = 0.0;
    for (int m : component.maps) {
      if (!octrees[m].tree) continue;
      inputs.push_back({octrees[m].tree.get(),
                        {result.T_component_map[m], *out.z_m[m]},
                        result.placed_by[m] == PlacedBy::kFixed});
      const double r = octrees[m].tree->getResolution();
      resolution_m = resolution_m > 0.0 ? std::min(resolution_m, r) : r;  // the finest
    }
    if (inputs.empty()) continue;
    out.merged_files[c] = "merged_" + std::to_string(c) + ".bt";
    SaveOctree(*MergeOctrees(inputs, resolution_m), dir / out.merged_files[c], protect, mode);
  }
  out.write_ms = MillisecondsSince(start);
  return out;
}

void AddOctreesToReport(nlohmann::json& report, const std::vector<JobOctree>& octrees,
                        const OctreeOutputs& outputs) {
  double projection_ms = 0.0;
  bool any = false;
  for (std::size_t m = 0; m < octrees.size(); ++m) {
    if (!octrees[m].tree) continue;
    any = true;
    projection_ms += octrees[m].projection_ms;
    nlohmann::json& map = report["maps"][m];
    map["pose"]["z"] = outputs.z_m[m].value_or(0.0);
    map["floor_z"] = octrees[m].floor_z_m;
  }
  if (!any) return;  // a 2-D job's report is unchanged
  for (std::size_t c = 0; c < outputs.merged_files.size(); ++c) {
    if (!outputs.merged_files[c].empty()) {
      report["components"][c]["merged_octree"] = outputs.merged_files[c];
    }
  }
  report["timing_ms"]["octree_projection"] = projection_ms;
  report["timing_ms"]["octree_write"] = outputs.write_ms;
}

}  // namespace fleetmerge
