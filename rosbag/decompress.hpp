// The chunk compressions of robot bags: bz2 and lz4 (ROS 1 bags; roslz4 writes LZ4 frames),
// zstd and lz4 frames (MCAP). Each takes the size the container announces for the output and
// throws fleetmerge::Error starting with `context` when the data is corrupt or its size differs.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace fleetmerge {

// A chunk announcing more than this is refused before allocating (1 GiB: rosbag's and MCAP
// writers' chunks are kilobytes to a few megabytes).
inline constexpr std::size_t kMaxChunkBytes = std::size_t{1} << 30;

std::string DecompressBz2(std::string_view data, std::size_t size, const std::string& context);
std::string DecompressLz4Frame(std::string_view data, std::size_t size, const std::string& context);
std::string DecompressZstd(std::string_view data, std::size_t size, const std::string& context);
// One zstd frame whose size its header may or may not give (rosbag2's MESSAGE compression).
std::string DecompressZstdFrame(std::string_view data, const std::string& context);

}  // namespace fleetmerge
