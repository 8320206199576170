// rosbag/mcap_writer.hpp and the CDR encoders, read back by fleetmerge's readers (rosbag/
// mcap_file.hpp, rosbag/occupancy_grid_msg.hpp), which were written to read other writers'
// files. The independent readers (@mcap/core, @foxglove/rosmsg2-serialization) read the
// result set's bag in result_set_ros_test.cpp.
#include "rosbag/mcap_writer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include "core/error.hpp"
#include "rosbag/mcap_file.hpp"
#include "rosbag/merged_bag.hpp"
#include "rosbag/occupancy_grid_msg.hpp"
#include "rosbag/ros_time.hpp"
#include "tests/support/shared_data.hpp"

namespace fleetmerge {
namespace {

namespace fs = std::filesystem;

void Write(const fs::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out << bytes;
}

TEST(Crc32, CheckValueOfTheStandard) {
  const std::string text = "123456789";  // CRC-32/ISO-HDLC's check value
  EXPECT_EQ(Crc32(text, 0, text.size()), 0xCBF43926u);
  EXPECT_EQ(Crc32(text, 0, 0), 0u);
}

TEST(McapWriter, MessagesReadBackByTheReader) {
  McapWriter writer("ros2", "test");
  const std::uint16_t schema = writer.AddSchema("std_msgs/msg/String", "ros2msg", "string data\n");
  const std::uint16_t a = writer.AddChannel(schema, "/a", "cdr", {{"offered_qos_profiles", ""}});
  const std::uint16_t b = writer.AddChannel(schema, "/b", "cdr", {});
  writer.AddMessage(a, 10, 10, "first on a");
  writer.AddMessage(b, 15, 15, std::string("\0binary\xff", 8));
  writer.AddMessage(a, 30, 29, "last on a");
  writer.AddMetadata("rosbag2", {{"serialized_metadata", "version: 9\n"}});
  const fs::path file = testing::MakeTempDir("mcap_writer") / "w.mcap";
  Write(file, writer.Finish());

  const std::vector<BagTopic> topics = McapTopics(file);
  ASSERT_EQ(topics.size(), 2u);
  EXPECT_EQ(topics[0].name, "/a");
  EXPECT_EQ(topics[0].type, "std_msgs/msg/String");
  EXPECT_EQ(topics[0].messages, 2u);
  EXPECT_EQ(topics[1].name, "/b");
  EXPECT_EQ(topics[1].messages, 1u);
  const auto last_a = McapLastMessage(file, "/a");
  ASSERT_TRUE(last_a.has_value());
  EXPECT_EQ(last_a->data, "last on a");
  EXPECT_EQ(last_a->log_time_ns, 30);
  const auto last_b = McapLastMessage(file, "/b");
  ASSERT_TRUE(last_b.has_value());
  EXPECT_EQ(last_b->data, std::string("\0binary\xff", 8));
  EXPECT_FALSE(McapLastMessage(file, "/c").has_value());
}

TEST(McapWriter, RefusesUnknownIds) {
  McapWriter writer("ros2", "test");
  EXPECT_THROW(writer.AddChannel(1, "/a", "cdr", {}), Error);
  const std::uint16_t schema = writer.AddSchema("x/msg/Y", "ros2msg", "");
  EXPECT_THROW(writer.AddMessage(1, 0, 0, ""), Error);
  EXPECT_NO_THROW(writer.AddChannel(schema, "/a", "cdr", {}));
}

TEST(RosTime, SecondsRoundDown) {
  EXPECT_EQ(RosTimeOf(1'500'000'001).sec, 1);
  EXPECT_EQ(RosTimeOf(1'500'000'001).nanosec, 500'000'001u);
  EXPECT_EQ(RosTimeOf(-1).sec, -1);
  EXPECT_EQ(RosTimeOf(-1).nanosec, 999'999'999u);
}

// Encoding then decoding (the decoder reads recorded bags) gives every cell, the origin and the
// frame back, at random states, sizes and yaws.
TEST(OccupancyGridCdr, EncodeDecodeRoundTrip) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    const int width = 1 + static_cast<int>(rng() % 40), height = 1 + static_cast<int>(rng() % 40);
    const double yaw = std::uniform_real_distribution<double>(-M_PI, M_PI)(rng);
    const GridGeometry geometry(0.05, {width, height}, Pose2(-12.5 + trial, 3.25, yaw));
    OccupancyGrid grid(geometry);
    for (int j = 0; j < height; ++j) {
      for (int i = 0; i < width; ++i) grid.set({i, j}, static_cast<CellState>(rng() % 3));
    }
    const std::int64_t stamp_ns = 1'700'000'000'123'456'789 + trial;
    const std::string frame = trial % 2 ? "map" : "map_" + std::to_string(trial);
    const std::string bytes = EncodeCdrOccupancyGrid(grid, frame, stamp_ns);
    const OccupancyGridMsg msg = DecodeCdrOccupancyGrid(bytes, "test");
    EXPECT_EQ(msg.frame_id, frame);
    EXPECT_EQ(msg.stamp_ns, stamp_ns);
    EXPECT_EQ(msg.origin_z_m, 0.0);
    const OccupancyGrid back = OccupancyGridFromMsg(msg, "test", kDefaultMaxMapCells);
    ASSERT_EQ(back.width(), width);
    ASSERT_EQ(back.height(), height);
    EXPECT_EQ(cv::countNonZero(back.cells() != grid.cells()), 0) << "trial " << trial;
    EXPECT_EQ(back.geometry().resolution_m(), 0.05);
    EXPECT_EQ(back.geometry().T_map_grid().x_m(), -12.5 + trial);
    EXPECT_NEAR(back.geometry().T_map_grid().yaw_rad(), yaw, 1e-12);
    // ROS's values: every byte is 0, 100 or -1 (0xff), as map_server publishes.
    for (std::size_t k = 0; k < msg.data.size(); ++k) {
      const int v = static_cast<signed char>(msg.data[k]);
      ASSERT_TRUE(v == 0 || v == 100 || v == -1) << v;
    }
  }
}

TEST(MergedBag, RefusesBadAndRepeatedTopics) {
  const OccupancyGrid grid(GridGeometry(0.1, {2, 2}));
  EXPECT_THROW(MakeMergedBag({{"map", "map", &grid}}, {}, 0), Error);
  EXPECT_THROW(MakeMergedBag({{"/a b", "map", &grid}}, {}, 0), Error);
  EXPECT_THROW(MakeMergedBag({{"/map", "map", &grid}, {"/map", "map", &grid}}, {}, 0), Error);
  EXPECT_THROW(MakeMergedBag({{"/tf_static", "map", &grid}}, {}, 0), Error);
  EXPECT_NO_THROW(MakeMergedBag({{"/merged_1/map", "map_1", &grid}}, {}, 0));
}

}  // namespace
}  // namespace fleetmerge
