#include "io/octree_job_keys.hpp"

namespace fleetmerge {

void ReadOctreeOptions(const YamlField& field, OctreeOptions& options, const YamlErrors& errors) {
  const YamlMapping octree(field, {"band_min_m", "band_max_m"}, "a mapping", errors);
  // +-10 m: a band above the floor of one storey; anything larger is a typo (centimetres?).
  const auto min = octree.Find("band_min_m"), max = octree.Find("band_max_m");
  if (min) options.band_min_m = ReadNumber(*min, -10.0, 10.0, false, errors);
  if (max) options.band_max_m = ReadNumber(*max, -10.0, 10.0, false, errors);
  if (!(options.band_min_m < options.band_max_m)) {
    const YamlField& at = max ? *max : *min;
    errors.Fail(at.key, at.line,
                "expected band_min_m < band_max_m, got " + std::to_string(options.band_min_m) +
                    " and " + std::to_string(options.band_max_m));
  }
}

}  // namespace fleetmerge
