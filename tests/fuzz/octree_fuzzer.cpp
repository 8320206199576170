// Fuzzes the octree reader (io/octree_io: header check, data walk, then OctoMap). Every input is
// written both as tree.bt and as tree.ot, so each input exercises the reader of its own kind and
// the other kind's refusal. A loaded tree must be non-empty and its leaves walkable at OcTree's
// depth. Anything but a clean load or a fleetmerge::Error (a crash, a sanitizer report, another
// exception, a hang) is a finding.
#include <octomap/OcTree.h>

#include <cstdlib>

#include "core/error.hpp"
#include "io/octree_io.hpp"
#include "tests/fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace fleetmerge;
  const std::filesystem::path dir = fuzz::ScratchDir();
  for (const char* name : {"tree.bt", "tree.ot"}) {
    const std::filesystem::path path = dir / name;
    fuzz::WriteBytes(path, reinterpret_cast<const char*>(data), size);
    try {
      CheckOctreeFile(path);
    } catch (const Error&) {
    }
    try {
      const auto tree = LoadOctree(path);
      if (!tree || tree->size() == 0) abort();  // loaded trees are not empty
      std::size_t leaves = 0;
      for (auto it = tree->begin_leafs(); it != tree->end_leafs(); ++it) {
        if (it.getDepth() > tree->getTreeDepth()) abort();
        ++leaves;
      }
      if (leaves > tree->size()) abort();
    } catch (const Error&) {
    }
  }
  return 0;
}
