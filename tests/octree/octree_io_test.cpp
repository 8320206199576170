// io/octree_io: .bt and .ot round trips (same leaves, same occupancy; .ot also the same log-odds)
// and every refusal: not an octree, the other kind, another tree type, an empty tree, a truncated
// file, a missing file, a wrong extension, writing an empty tree or over an input.
#include "io/octree_io.hpp"

#include <gtest/gtest.h>
#include <octomap/ColorOcTree.h>
#include <octomap/OcTree.h>

#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <tuple>

#include "core/error.hpp"
#include "tests/support/files.hpp"
#include "tests/support/shared_data.hpp"

namespace fleetmerge {
namespace {

namespace fs = std::filesystem;

// A random tree: 2000 random updates (hits and misses) in a 2 m cube at 5 cm, pruned.
octomap::OcTree RandomTree(unsigned seed) {
  octomap::OcTree tree(0.05);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> coord(-1.0, 1.0);
  for (int i = 0; i < 2000; ++i) {
    tree.updateNode(octomap::point3d(coord(rng), coord(rng), coord(rng)), i % 3 != 0);
  }
  // A free block of 8^3 voxels that prunes into one leaf.
  for (double x = 1.2; x < 1.6; x += 0.05)
    for (double y = 1.2; y < 1.6; y += 0.05)
      for (double z = 1.2; z < 1.6; z += 0.05) tree.updateNode(x + 0.01, y + 0.01, z + 0.01, false);
  tree.prune();
  return tree;
}

// Leaves by (key, depth): occupancy and log-odds.
using Leaves = std::map<std::tuple<int, int, int, unsigned>, std::pair<bool, float>>;
Leaves LeavesOf(const octomap::OcTree& tree) {
  Leaves leaves;
  for (auto it = tree.begin_leafs(); it != tree.end_leafs(); ++it) {
    const auto k = it.getKey();
    leaves[{k[0], k[1], k[2], it.getDepth()}] = {tree.isNodeOccupied(*it), it->getLogOdds()};
  }
  return leaves;
}

void WriteText(const fs::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

std::string ErrorOf(const fs::path& path) {
  try {
    LoadOctree(path);
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(OctreeIo, BinaryRoundTripKeepsLeavesAndOccupancy) {
  const fs::path dir = testing::MakeTempDir("octree_io_bt");
  octomap::OcTree tree = RandomTree(1);
  SaveOctree(tree, dir / "t.bt");
  const auto read = LoadOctree(dir / "t.bt");
  EXPECT_DOUBLE_EQ(read->getResolution(), 0.05);
  // .bt keeps occupancy only: compare against the maximum-likelihood tree, pruned.
  tree.toMaxLikelihood();
  tree.prune();
  const Leaves expected = LeavesOf(tree), actual = LeavesOf(*read);
  ASSERT_GT(expected.size(), 1000u);
  ASSERT_EQ(actual.size(), expected.size());
  for (const auto& [key, value] : expected) {
    ASSERT_TRUE(actual.count(key));
    EXPECT_EQ(actual.at(key).first, value.first);
  }
}

TEST(OctreeIo, FullRoundTripKeepsLogOdds) {
  const fs::path dir = testing::MakeTempDir("octree_io_ot");
  const octomap::OcTree tree = RandomTree(2);
  SaveOctree(tree, dir / "t.OT");  // the extension in any case
  const auto read = LoadOctree(dir / "t.OT");
  EXPECT_EQ(LeavesOf(*read), LeavesOf(tree));
  EXPECT_EQ(read->size(), tree.size());
}

// SaveOctree writes a .bt's data node by node (io/octree_io.cpp: OctoMap's own writers print on
// stderr, which MergeCliOctrees.QuietMergeOfOctreesPrintsNothingOnStderr checks): the same bytes
// as OctoMap's writeBinaryConst() after the header.
TEST(OctreeIo, BinaryDataAreOctoMapsOwnBytes) {
  const fs::path dir = testing::MakeTempDir("octree_io_bytes");
  const octomap::OcTree tree = RandomTree(4);
  SaveOctree(tree, dir / "t.bt");
  std::ostringstream octomap_bytes;
  tree.writeBinaryConst(octomap_bytes);
  const std::string expected = octomap_bytes.str(), written = testing::ReadFile(dir / "t.bt");
  const std::string data_line = "\ndata\n";
  ASSERT_NE(expected.find(data_line), std::string::npos);
  ASSERT_NE(written.find(data_line), std::string::npos);
  ASSERT_GT(expected.size() - expected.find(data_line), 1000u);
  EXPECT_EQ(written.substr(written.find(data_line)), expected.substr(expected.find(data_line)));
}

TEST(OctreeIo, RefusesFilesThatAreNotOcTrees) {
  const fs::path dir = testing::MakeTempDir("octree_io_errors");
  WriteText(dir / "text.bt", "P5\n3 3\n255\nabcdefghi");
  EXPECT_NE(ErrorOf(dir / "text.bt").find("text.bt: not an OctoMap octree"), std::string::npos)
      << ErrorOf(dir / "text.bt");

  const octomap::OcTree tree = RandomTree(3);
  SaveOctree(tree, dir / "full.ot");
  fs::copy_file(dir / "full.ot", dir / "renamed.bt");
  EXPECT_NE(ErrorOf(dir / "renamed.bt").find("rename it to .ot"), std::string::npos)
      << ErrorOf(dir / "renamed.bt");

  octomap::ColorOcTree colour(0.1);
  colour.updateNode(octomap::point3d(0.f, 0.f, 0.f), true);
  std::ostringstream colour_bytes;
  colour.write(colour_bytes);
  WriteText(dir / "colour.ot", colour_bytes.str());
  EXPECT_NE(ErrorOf(dir / "colour.ot").find("of type 'ColorOcTree'; expected 'OcTree'"),
            std::string::npos)
      << ErrorOf(dir / "colour.ot");

  octomap::OcTree empty(0.1);
  std::ostringstream empty_bytes;
  empty.writeBinaryConst(empty_bytes);
  WriteText(dir / "empty.bt", empty_bytes.str());
  EXPECT_NE(ErrorOf(dir / "empty.bt").find("empty (size 0)"), std::string::npos)
      << ErrorOf(dir / "empty.bt");

  std::ostringstream full;
  tree.writeBinaryConst(full);
  WriteText(dir / "truncated.bt", full.str().substr(0, full.str().size() / 2));
  EXPECT_NE(ErrorOf(dir / "truncated.bt").find("truncated or corrupt"), std::string::npos)
      << ErrorOf(dir / "truncated.bt");
  WriteText(dir / "header_only.bt", full.str().substr(0, 40));
  EXPECT_NE(ErrorOf(dir / "header_only.bt").find("without a 'data' line"), std::string::npos)
      << ErrorOf(dir / "header_only.bt");

  EXPECT_NE(ErrorOf(dir / "missing.bt").find("missing.bt: cannot open"), std::string::npos);
  EXPECT_NE(ErrorOf(dir / "tree.pgm").find("ending in .bt or .ot"), std::string::npos);
  EXPECT_THROW(CheckOctreeFile(dir / "colour.ot"), Error);
  EXPECT_NO_THROW(CheckOctreeFile(dir / "full.ot"));
}

TEST(OctreeIo, RefusesToWriteAnEmptyTreeOrOverAnInput) {
  const fs::path dir = testing::MakeTempDir("octree_io_write");
  EXPECT_THROW(SaveOctree(octomap::OcTree(0.1), dir / "e.bt"), Error);
  EXPECT_FALSE(fs::exists(dir / "e.bt"));
  const octomap::OcTree tree = RandomTree(4);
  SaveOctree(tree, dir / "in.bt");
  const auto before = fs::file_size(dir / "in.bt");
  EXPECT_THROW(SaveOctree(RandomTree(5), dir / "in.bt", {dir / "in.bt"}), Error);
  EXPECT_EQ(fs::file_size(dir / "in.bt"), before);
  EXPECT_TRUE(IsOctreePath("a/b.Bt"));
  EXPECT_FALSE(IsOctreePath("a/b.yaml"));
}

}  // namespace
}  // namespace fleetmerge
