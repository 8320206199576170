#include "rosbag/occupancy_grid_msg.hpp"

#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "core/error.hpp"
#include "rosbag/byte_reader.hpp"
#include "rosbag/byte_writer.hpp"
#include "rosbag/ros_time.hpp"

namespace fleetmerge {
namespace {

// CDR: primitives are aligned to their size, counted from the end of the encapsulation header.
class CdrReader {
 public:
  CdrReader(std::string_view payload, bool big_endian, const std::string& context)
      : reader_(payload, context + ": CDR payload"), big_endian_(big_endian) {}

  template <typename T>
  T Read(const char* what) {
    Align(sizeof(T), what);
    return reader_.Read<T>(what, big_endian_);
  }
  std::string String(const char* what) {
    const std::uint32_t length = Read<std::uint32_t>(what);  // includes the terminating NUL
    std::string_view bytes = reader_.Bytes(length, what);
    if (!bytes.empty() && bytes.back() == '\0') bytes.remove_suffix(1);
    return std::string(bytes);
  }
  std::string_view Bytes(std::size_t n, const char* what) { return reader_.Bytes(n, what); }
  std::size_t remaining() const { return reader_.remaining(); }

 private:
  void Align(std::size_t size, const char* what) {
    const std::size_t pad = (size - reader_.offset() % size) % size;
    reader_.Skip(pad, what);
  }
  ByteReader reader_;
  bool big_endian_;
};

// info.resolution is a float32: 0.05 arrives as 0.0500000007. The shortest decimal that is the
// same float (what the robot's YAML said) keeps a bag's map at exactly the resolution of the
// same map as a file, so merging them does not resample one of them.
double ShortestDecimal(float value) {
  for (int digits = 1; digits <= 9; ++digits) {
    char text[32];
    std::snprintf(text, sizeof(text), "%.*g", digits, static_cast<double>(value));
    const double parsed = std::strtod(text, nullptr);
    if (!(std::fabs(parsed) <= FLT_MAX)) continue;  // the float conversion would overflow
    if (static_cast<float>(parsed) == value) return parsed;
  }
  return value;
}

}  // namespace

OccupancyGridMsg DecodeRos1OccupancyGrid(std::string_view bytes, const std::string& context) {
  ByteReader r(bytes, context + ": nav_msgs/OccupancyGrid message");
  OccupancyGridMsg msg;
  r.U32("header.seq");
  const std::uint32_t sec = r.U32("header.stamp"), nsec = r.U32("header.stamp");
  msg.stamp_ns = static_cast<std::int64_t>(sec) * 1'000'000'000 + nsec;
  const std::uint32_t frame_length = r.U32("header.frame_id length");
  msg.frame_id = std::string(r.Bytes(frame_length, "header.frame_id"));
  r.Skip(8, "info.map_load_time");
  msg.resolution_m = ShortestDecimal(r.Read<float>("info.resolution"));
  msg.width = r.U32("info.width");
  msg.height = r.U32("info.height");
  msg.origin_x_m = r.Read<double>("info.origin.position");
  msg.origin_y_m = r.Read<double>("info.origin.position");
  msg.origin_z_m = r.Read<double>("info.origin.position");
  msg.qx = r.Read<double>("info.origin.orientation");
  msg.qy = r.Read<double>("info.origin.orientation");
  msg.qz = r.Read<double>("info.origin.orientation");
  msg.qw = r.Read<double>("info.origin.orientation");
  const std::uint32_t cells = r.U32("data length");
  msg.data = r.Bytes(cells, "data");
  return msg;
}

OccupancyGridMsg DecodeCdrOccupancyGrid(std::string_view bytes, const std::string& context) {
  ByteReader header(bytes, context + ": CDR message");
  const std::string_view encapsulation = header.Bytes(4, "encapsulation header");
  // 0x0000 CDR_BE, 0x0001 CDR_LE (what rmw_fastrtps and cyclonedds write for plain types).
  if (encapsulation[0] != 0 || (encapsulation[1] != 0 && encapsulation[1] != 1)) {
    std::ostringstream m;
    m << context << ": CDR encapsulation " << int(static_cast<unsigned char>(encapsulation[0]))
      << "," << int(static_cast<unsigned char>(encapsulation[1]))
      << " is not plain CDR (expected 0,0 big-endian or 0,1 little-endian)";
    throw Error(m.str());
  }
  CdrReader r(bytes.substr(4), encapsulation[1] == 0, context);
  OccupancyGridMsg msg;
  const std::int32_t sec = r.Read<std::int32_t>("header.stamp.sec");
  const std::uint32_t nsec = r.Read<std::uint32_t>("header.stamp.nanosec");
  msg.stamp_ns = static_cast<std::int64_t>(sec) * 1'000'000'000 + nsec;
  msg.frame_id = r.String("header.frame_id");
  r.Read<std::int32_t>("info.map_load_time.sec");
  r.Read<std::uint32_t>("info.map_load_time.nanosec");
  msg.resolution_m = ShortestDecimal(r.Read<float>("info.resolution"));
  msg.width = r.Read<std::uint32_t>("info.width");
  msg.height = r.Read<std::uint32_t>("info.height");
  msg.origin_x_m = r.Read<double>("info.origin.position.x");
  msg.origin_y_m = r.Read<double>("info.origin.position.y");
  msg.origin_z_m = r.Read<double>("info.origin.position.z");
  msg.qx = r.Read<double>("info.origin.orientation.x");
  msg.qy = r.Read<double>("info.origin.orientation.y");
  msg.qz = r.Read<double>("info.origin.orientation.z");
  msg.qw = r.Read<double>("info.origin.orientation.w");
  const std::uint32_t cells = r.Read<std::uint32_t>("data length");
  msg.data = r.Bytes(cells, "data");
  return msg;
}

OccupancyGrid OccupancyGridFromMsg(const OccupancyGridMsg& msg, const std::string& context,
                                   std::int64_t max_cells) {
  std::ostringstream m;
  m.precision(17);
  if (!std::isfinite(msg.resolution_m) || !(msg.resolution_m > 0.0)) {
    m << context << ": info.resolution is " << msg.resolution_m
      << ", expected a finite number of metres per cell > 0";
    throw Error(m.str());
  }
  for (double v :
       {msg.origin_x_m, msg.origin_y_m, msg.origin_z_m, msg.qx, msg.qy, msg.qz, msg.qw}) {
    if (!std::isfinite(v)) {
      throw Error(context + ": info.origin has a value that is not a finite number");
    }
  }
  const double norm2 = msg.qx * msg.qx + msg.qy * msg.qy + msg.qz * msg.qz + msg.qw * msg.qw;
  if (norm2 < 1e-12) {
    throw Error(context + ": info.origin.orientation is the zero quaternion, expected a rotation");
  }
  const std::uint64_t cells = static_cast<std::uint64_t>(msg.width) * msg.height;
  if (cells != msg.data.size()) {
    m << context << ": data has " << msg.data.size()
      << " cells, expected width x height = " << msg.width << " x " << msg.height << " = " << cells;
    throw Error(m.str());
  }
  if (cells == 0) {  // consistent, but not a map: nothing downstream has a cell to work on
    m << context << ": info.width x info.height is " << msg.width << " x " << msg.height
      << ": the map has no cells";
    throw Error(m.str());
  }
  if (msg.width > 0x7fffffffu || msg.height > 0x7fffffffu ||
      cells > static_cast<std::uint64_t>(max_cells)) {
    m << context << ": " << msg.width << " x " << msg.height << " cells is more than the limit of "
      << max_cells << " cells (--max-map-cells)";
    throw Error(m.str());
  }
  // Yaw of a quaternion (ZYX Euler); normalising first keeps a slightly off-unit one exact.
  const double n = std::sqrt(norm2);
  const double x = msg.qx / n, y = msg.qy / n, z = msg.qz / n, w = msg.qw / n;
  const double yaw_rad = std::atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z));
  const GridGeometry geometry(msg.resolution_m,
                              {static_cast<int>(msg.width), static_cast<int>(msg.height)},
                              Pose2(msg.origin_x_m, msg.origin_y_m, yaw_rad));
  cv::Mat1b states(static_cast<int>(msg.height), static_cast<int>(msg.width));
  for (std::uint64_t k = 0; k < cells; ++k) {
    const int v = static_cast<signed char>(msg.data[k]);
    CellState s = CellState::kUnknown;
    if (v >= 0 && v <= 25) s = CellState::kFree;
    if (v >= 65 && v <= 100) s = CellState::kOccupied;
    states(static_cast<int>(k / msg.width), static_cast<int>(k % msg.width)) =
        static_cast<std::uint8_t>(s);
  }
  return OccupancyGrid(geometry, states);
}

std::string EncodeCdrOccupancyGrid(const OccupancyGrid& grid, const std::string& frame_id,
                                   std::int64_t stamp_ns) {
  const RosTime stamp = RosTimeOf(stamp_ns);
  const GridGeometry& geometry = grid.geometry();
  const Pose2& origin = geometry.T_map_grid();
  const std::size_t cells = static_cast<std::size_t>(grid.width()) * grid.height();
  CdrWriter w;
  w.Reserve(cells + frame_id.size() + 128);  // the header's fields are under 128 bytes
  w.Put(stamp.sec);                          // header
  w.Put(stamp.nanosec);
  w.String(frame_id);
  w.Put(stamp.sec);  // info.map_load_time
  w.Put(stamp.nanosec);
  w.Put(static_cast<float>(geometry.resolution_m()));
  w.Put(static_cast<std::uint32_t>(grid.width()));
  w.Put(static_cast<std::uint32_t>(grid.height()));
  const double half_yaw = 0.5 * origin.yaw_rad();
  for (double v : {origin.x_m(), origin.y_m(), 0.0,                      // position
                   0.0, 0.0, std::sin(half_yaw), std::cos(half_yaw)}) {  // orientation x y z w
    w.Put(v);
  }
  char* data = w.ByteSequenceToFill(cells);
  std::size_t k = 0;
  for (int j = 0; j < grid.height(); ++j) {
    for (int i = 0; i < grid.width(); ++i, ++k) {
      switch (static_cast<CellState>(grid.cells()(j, i))) {
        case CellState::kFree:
          data[k] = 0;
          break;
        case CellState::kOccupied:
          data[k] = 100;
          break;
        default:
          data[k] = static_cast<char>(-1);
      }
    }
  }
  return w.Release();
}

}  // namespace fleetmerge
