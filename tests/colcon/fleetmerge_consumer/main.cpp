// Pairs a 4 x 3 m room with the same room shifted by (1.0 m, 0.5 m) and prints the best pose of
// the second map's frame in the first's, the header's version and the library's.
#include <cstdio>
#include <fleetmerge/fleetmerge.hpp>
#include <vector>

int main() {
  const int w = 120, h = 100, shift_x = 20, shift_y = 10;  // cells of 5 cm
  std::vector<std::int8_t> a(w * h, -1), b(w * h, -1);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const bool room = x >= 30 && x < 110 && y >= 20 && y < 80;  // an L-shaped room with a pillar
      const bool wall = room && (x == 30 || x == 109 || y == 20 || y == 79 || (x == 70 && y < 50));
      if (room) a[y * w + x] = wall ? 100 : 0;
    }
  }
  for (int y = 0; y + shift_y < h; ++y) {
    for (int x = 0; x + shift_x < w; ++x) b[y * w + x] = a[(y + shift_y) * w + x + shift_x];
  }
  const fleetmerge::Map map_a(a, w, h, 0.05, {0, 0, 0}, "a"), map_b(b, w, h, 0.05, {0, 0, 0}, "b");
  const fleetmerge::Hypothesis best = fleetmerge::Pair(map_a, map_b).front();
  std::printf("%.3f %.3f %.4f %.3f %s %s\n", best.x, best.y, best.yaw, best.omega,
              FLEETMERGE_VERSION_STRING, fleetmerge::Version().c_str());
  return 0;
}
