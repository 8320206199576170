// Uses the installed fleetmerge library as a mission-control server would:
//   merge_fleet pair A.yaml B.yaml [N]   the N best poses of B's frame in A's, one per line:
//                                        "x y yaw omega" (17 significant digits)
//   merge_fleet merge OUT A.yaml B.yaml ...  merges the maps (files written to OUT) and prints
//                                        where each map went and the merged maps' sizes
//   merge_fleet memory                   builds two maps in memory and pairs them
//   merge_fleet version                  the header's version macros and the library's version;
//                                        exit 1 when they differ (a header from another release)
#include <cstdio>
#include <exception>
#include <fleetmerge/fleetmerge.hpp>
#include <string>
#include <vector>

namespace {

int PairFiles(const std::string& a_path, const std::string& b_path, int n) {
  fleetmerge::Options options;
  options.hypotheses = n;
  const fleetmerge::Map a = fleetmerge::LoadMap(a_path);
  const fleetmerge::Map b = fleetmerge::LoadMap(b_path);
  for (const fleetmerge::Hypothesis& h : fleetmerge::Pair(a, b, options)) {
    std::printf("%.17g %.17g %.17g %.17g\n", h.x, h.y, h.yaw, h.omega);
  }
  return 0;
}

int MergeFiles(const std::string& out, const std::vector<std::string>& paths) {
  const fleetmerge::MergeResult result = fleetmerge::MergeFiles(paths, {}, out);
  for (const fleetmerge::MapPlacement& m : result.maps) {
    std::printf("%s component %d pose %.17g %.17g %.17g\n", m.name.c_str(), m.component, m.pose.x,
                m.pose.y, m.pose.yaw);
  }
  for (const fleetmerge::Component& c : result.components) {
    if (c.merged)
      std::printf("merged %d: %d x %d cells\n", c.id, c.merged->width(), c.merged->height());
  }
  return 0;
}

// Two views of one L-shaped room, the second shifted by (1.0 m, 0.5 m): OccupancyGrid data as a
// ROS node receives it (int8, -1 unknown, 0..100, row 0 at the origin).
int InMemory() {
  const int w = 120, h = 100;
  const double resolution_m = 0.05;
  const auto room = [&](int i, int j) -> std::int8_t {
    const bool wall = i == 10 || j == 10 || i == 100 || j == 80 || (i == 60 && j > 40);
    const bool inside = i > 10 && i < 100 && j > 10 && j < 80;
    return wall ? 100 : inside ? 0 : -1;
  };
  std::vector<std::int8_t> a(w * h), b(w * h);
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      a[j * w + i] = room(i, j);
      b[j * w + i] = room(i + 20, j + 10);  // b's cell (i, j) is a's (i + 20, j + 10)
    }
  }
  const fleetmerge::Map map_a(a, w, h, resolution_m, {0.0, 0.0, 0.0}, "a");
  const fleetmerge::Map map_b(b, w, h, resolution_m, {0.0, 0.0, 0.0}, "b");
  const fleetmerge::Hypothesis best = fleetmerge::Pair(map_a, map_b).front();
  std::printf("%.17g %.17g %.17g %.17g\n", best.x, best.y, best.yaw, best.omega);
  return 0;
}

// FLEETMERGE_VERSION_* are the header's (compile time), Version() the library's (run time).
int PrintVersion() {
  const std::string from_numbers = std::to_string(FLEETMERGE_VERSION_MAJOR) + "." +
                                   std::to_string(FLEETMERGE_VERSION_MINOR) + "." +
                                   std::to_string(FLEETMERGE_VERSION_PATCH);
  std::printf("header %s (%s) library %s\n", FLEETMERGE_VERSION_STRING, from_numbers.c_str(),
              fleetmerge::Version().c_str());
  const bool same = from_numbers == FLEETMERGE_VERSION_STRING &&
                    fleetmerge::Version() == FLEETMERGE_VERSION_STRING;
  return same ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const std::string command = argc > 1 ? argv[1] : "";
    if (command == "pair" && (argc == 4 || argc == 5)) {
      return PairFiles(argv[2], argv[3], argc == 5 ? std::stoi(argv[4]) : 4);
    }
    if (command == "merge" && argc >= 4) {
      return MergeFiles(argv[2], std::vector<std::string>(argv + 3, argv + argc));
    }
    if (command == "memory" && argc == 2) return InMemory();
    if (command == "version" && argc == 2) return PrintVersion();
    std::fprintf(stderr, "usage: merge_fleet pair A B [N] | merge OUT MAP... | memory | version\n");
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "merge_fleet: %s\n", e.what());
    return 1;
  }
}
