// Octrees (.bt, .ot) in a fleet-merging job: each is loaded with its floor plan
// (octree/octree_projection.hpp), which the 2-D pipeline merges like any map; afterwards every
// octree gets its vertical offset from the floor heights, and each component holding an octree
// gets one merged octree, merged_<c>.bt (octree/octree_merge.hpp).
//
// Vertical offset: all maps of a component stand on one floor, so an octree's z in the merged
// frame is (floor height of the component's 3-D reference) - (its own floor height). The 3-D
// reference is the component's reference map when it is an octree, else the component's first
// octree in job order; the merged octree's z = 0 is that octree's.
#pragma once

#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "io/atomic_file.hpp"
#include "io/map_io.hpp"
#include "job/job.hpp"
#include "octree/octree_options.hpp"
#include "pipeline/fleet_merge.hpp"

namespace octomap {
class OcTree;
}

namespace fleetmerge {

struct JobOctree {
  std::shared_ptr<const octomap::OcTree> tree;  // null for a 2-D map
  double floor_z_m = 0.0;                       // in the tree's frame
  double projection_ms = 0.0;                   // floor estimate + projection
};

// Reads an octree map and its floor plan. The LoadedMap's metadata names the octree file as
// yaml_path and image_path (so outputs never replace it) and its resolution.
LoadedMap LoadOctreeMap(const std::filesystem::path& path, const OctreeOptions& options,
                        JobOctree& octree);

// Per map: its vertical offset in its component's merged frame (octrees only, see above).
std::vector<std::optional<double>> VerticalOffsets(const FleetResult& result,
                                                   const std::vector<JobOctree>& octrees);

struct OctreeOutputs {
  std::vector<std::optional<double>> z_m;  // per map: its vertical offset (octrees only)
  std::vector<std::string> merged_files;   // per component: "merged_<c>.bt", or empty
  double write_ms = 0.0;                   // merging and writing the octrees
};

// `octrees` has one entry per job map. Writes dir/merged_<c>.bt for each component that has an
// octree and is merged (two or more maps, a one-map job, or a fixed map alone), atomically
// (WriteFileAtomically with `mode`), never over `protect`.
OctreeOutputs WriteMergedOctrees(const FleetResult& result, const std::vector<JobOctree>& octrees,
                                 const std::filesystem::path& dir,
                                 const std::vector<std::filesystem::path>& protect,
                                 AtomicWrite mode = AtomicWrite::kDurable);

// report.json additions: maps[m].pose.z and maps[m].floor_z for octrees, components[c].
// merged_octree, timing_ms.octree_projection (summed over the octrees) and octree_write.
void AddOctreesToReport(nlohmann::json& report, const std::vector<JobOctree>& octrees,
                        const OctreeOutputs& outputs);

}  // namespace fleetmerge
