// Names of maps given without one (io/map_names.hpp): file stems, unless they collide; then the
// shortest trailing folder path that makes every name unique; a bag's several topics add theirs.
#include "io/map_names.hpp"

#include <gtest/gtest.h>

#include <set>
#include <string>
#include <vector>

#include "core/error.hpp"

namespace fleetmerge {
namespace {

std::vector<std::string> Names(const std::vector<MapNameInput>& inputs,
                               const std::vector<std::string>& taken = {}) {
  return UniqueMapNames(inputs, taken);
}

TEST(MapNames, UniqueStemsStayAsToday) {
  EXPECT_EQ(Names({{"maps/robot_a.yaml", ""}, {"other/robot_b.yaml", ""}}),
            (std::vector<std::string>{"robot_a", "robot_b"}));
}

TEST(MapNames, MapSaverFolderPerRobotIsNamedByFolder) {
  EXPECT_EQ(Names({{"r1/map.yaml", ""}, {"r2/map.yaml", ""}, {"r3/map.yaml", ""}}),
            (std::vector<std::string>{"r1", "r2", "r3"}));
}

TEST(MapNames, DeeperFoldersWhenTheInnermostCollide) {
  EXPECT_EQ(Names({{"/m/day1/r1/map.yaml", ""}, {"/m/day2/r1/map.yaml", ""}}),
            (std::vector<std::string>{"day1/r1", "day2/r1"}));
}

TEST(MapNames, OnlyCollidingMapsAreRenamed) {
  EXPECT_EQ(Names({{"a/map.yaml", ""}, {"b/map.yaml", ""}, {"c/office.yaml", ""}}),
            (std::vector<std::string>{"a", "b", "office"}));
}

TEST(MapNames, AFolderNameNeverTakesAnotherMapsName) {
  // r1/map.yaml would be "r1", but r1.yaml is already "r1": one more folder level.
  const auto names = Names({{"/x/r1/map.yaml", ""}, {"/y/r2/map.yaml", ""}, {"/z/r1.yaml", ""}});
  EXPECT_EQ(names[2], "r1");
  EXPECT_EQ(names[0], "x/r1");
  EXPECT_EQ(names[1], "y/r2");
}

TEST(MapNames, GivenNamesAreNeverReused) {
  const auto names = Names({{"/a/r1/map.yaml", ""}, {"/a/r2/map.yaml", ""}}, {"r1"});
  EXPECT_EQ(names, (std::vector<std::string>{"a/r1", "a/r2"}));
}

TEST(MapNames, BagTopicsAreAppended) {
  EXPECT_EQ(TopicForName("/robot1/map"), "robot1_map");
  EXPECT_EQ(TopicForName("map"), "map");
  EXPECT_EQ(Names({{"fleet.bag", "/robot1/map"}, {"fleet.bag", "/robot2/map"}}),
            (std::vector<std::string>{"fleet_robot1_map", "fleet_robot2_map"}));
  EXPECT_EQ(Names({{"/d/r1/run.bag", "/map"}, {"/d/r2/run.bag", "/map"}}),
            (std::vector<std::string>{"r1_map", "r2_map"}));
}

TEST(MapNames, EveryNameIsUniqueOnARandomLayout) {
  // Oracle: whatever the layout, names are pairwise distinct and distinct from the taken ones.
  std::vector<MapNameInput> inputs;
  const std::vector<std::string> folders = {"a", "b", "a/b", "b/a", "c/a/b", "r1", "map"};
  for (const auto& f : folders) {
    for (const auto& stem : {"map", "r1", "a"})
      inputs.push_back({"/root/" + f + "/" + stem + ".yaml", ""});
  }
  const auto names = Names(inputs, {"map", "b"});
  std::set<std::string> distinct(names.begin(), names.end());
  EXPECT_EQ(distinct.size(), names.size());
  EXPECT_EQ(distinct.count("map"), 0u);
  EXPECT_EQ(distinct.count("b"), 0u);
}

TEST(MapNames, TheSameFileAndTopicTwiceIsRefused) {
  EXPECT_THROW(Names({{"/a/map.yaml", ""}, {"/a/map.yaml", ""}}), Error);
}

}  // namespace
}  // namespace fleetmerge
