#include "octree/synthetic_octree.hpp"

#include <cmath>

#include "core/error.hpp"

namespace fleetmerge {

std::unique_ptr<octomap::OcTree> ExtrudeFloorPlan(const OccupancyGrid& plan,
                                                  const ExtrudeOptions& options) {
  const double r = plan.geometry().resolution_m();
  if (!(options.wall_height_m >= 2.0 * r)) {
    throw Error("ExtrudeFloorPlan: wall_height_m must be at least two voxels");
  }
  auto tree = std::make_unique<octomap::OcTree>(r);
  const float occupied = tree->getClampingThresMaxLog();
  const float free = tree->getClampingThresMinLog();
  const octomap::key_type floor_key = tree->coordToKey(options.floor_z_m - 0.5 * r);
  const octomap::key_type top_key =
      tree->coordToKey(options.floor_z_m + options.wall_height_m - 0.5 * r);
  for (int j = 0; j < plan.height(); ++j) {
    for (int i = 0; i < plan.width(); ++i) {
      const CellState state = plan.at({i, j});
      if (state == CellState::kUnknown) continue;
      const Eigen::Vector2d p = plan.geometry().CellCenter({i, j});
      const octomap::key_type kx = tree->coordToKey(p.x()), ky = tree->coordToKey(p.y());
      auto set = [&](int k, float value) {
        tree->setNodeValue(octomap::OcTreeKey(kx, ky, octomap::key_type(k)), value, true);
      };
      set(floor_key, occupied);  // under walls too: the slab runs beneath them
      const bool clutter = options.low_clutter && i % 7 == 3 && j % 7 == 3;
      for (int k = floor_key + 1; k <= top_key; ++k) {
        const bool low_object = clutter && k <= floor_key + std::max(1, int(0.1 / r));
        set(k, state == CellState::kOccupied || low_object ? occupied : free);
      }
      if (options.ceiling) set(top_key + 1, occupied);
    }
  }
  tree->updateInnerOccupancy();
  tree->prune();
  return tree;
}

}  // namespace fleetmerge
