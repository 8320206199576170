// Writes tests/data/octree/small.bt and small.ot with fleetmerge's SaveOctree (OctoMap's own
// encoding): a 4 x 4 x 3 block of 0.1 m voxels, an occupied floor layer under two free layers,
// observed to OctoMap's clamping log-odds. They are the valid octrees that
// tests/data/bad/generate.py cuts and corrupts and tests/fuzz/make_corpus.py seeds the octree
// fuzzer with. Built as write_small_octrees (not run by ctest):
//   ./build/tests/octree/write_small_octrees tests/data/octree
#include <octomap/OcTree.h>

#include <filesystem>
#include <iostream>

#include "io/octree_io.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: write_small_octrees <folder>\n";
    return 2;
  }
  const std::filesystem::path folder = argv[1];
  octomap::OcTree tree(0.1);
  for (int x = 0; x < 4; ++x) {
    for (int y = 0; y < 4; ++y) {
      for (int z = 0; z < 3; ++z) {
        // Voxel centres, all in the positive octant so the tree stays small.
        const octomap::point3d centre(0.05f + 0.1f * x, 0.05f + 0.1f * y, 0.05f + 0.1f * z);
        for (int hit = 0; hit < 10; ++hit) tree.updateNode(centre, z == 0);
      }
    }
  }
  fleetmerge::SaveOctree(tree, folder / "small.bt");
  fleetmerge::SaveOctree(tree, folder / "small.ot");
  std::cout << "wrote small.bt and small.ot: " << tree.size() << " nodes, "
            << tree.getNumLeafNodes() << " leaves\n";
  return 0;
}
