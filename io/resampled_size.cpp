#include "io/resampled_size.hpp"

#include <sstream>

#include "core/error.hpp"

namespace fleetmerge {

std::string MapLabel(const LoadedMap& map) {
  return map.bag ? map.bag->bag.string() + " topic " + map.bag->topic
                 : map.metadata.yaml_path.string();
}

void CheckResampledSizes(const std::vector<const LoadedMap*>& maps, double resolution_m,
                         std::int64_t max_cells) {
  if (maps.empty()) return;
  const LoadedMap* finest = maps.front();
  for (const LoadedMap* m : maps) {
    if (m->grid.geometry().resolution_m() < finest->grid.geometry().resolution_m()) finest = m;
  }
  const double target = resolution_m > 0.0 ? resolution_m : finest->grid.geometry().resolution_m();
  for (const LoadedMap* m : maps) {
    const double scale = m->grid.geometry().resolution_m() / target;  // > 1: more cells
    const double cells = (m->grid.width() * scale + 1.0) * (m->grid.height() * scale + 1.0);
    if (cells > static_cast<double>(max_cells)) {
      std::ostringstream out;
      out << MapLabel(*m) << ": its " << m->grid.width() << " x " << m->grid.height()
          << " cells of " << m->grid.geometry().resolution_m() << " m would become " << cells
          << " cells at " << target << " m per cell ("
          << (resolution_m > 0.0 ? std::string("the job's resolution")
                                 : "the finest resolution, that of " + MapLabel(*finest))
          << "), more than the limit of " << max_cells
          << " cells (--max-map-cells); check that resolution";
      throw Error(out.str());
    }
  }
}

}  // namespace fleetmerge
