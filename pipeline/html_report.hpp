// report.html: the page a person opens to see why maps merged or did not (issue 12). It is
// written beside report.json, into the same staging folder (io/result_folder.hpp), and opens
// offline from the folder: hand-written HTML, CSS and JavaScript inline in the one file, the
// report's data inline as JSON, and images that are files of the same set:
//   merged_<c>_preview.png  the merged map of each component (pipeline/preview.hpp), drawn at
//                           full resolution with the pose graph over it;
//   report_map_<m>.png      each map's cells at the report's resolution (RGBA: occupied black,
//                           free near-white, unknown transparent), one pixel per cell. The page
//                           tints two of them and draws b over a by a pair's hypothesis T_a_b
//                           on a canvas, so every hypothesis of every pair (N (N - 1) / 2 pairs)
//                           costs no file: N small images serve them all, loaded on first use.
// docs/report.md says how to read the page.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/occupancy_grid.hpp"
#include "core/pose2.hpp"
#include "io/atomic_file.hpp"
#include "io/map_io.hpp"
#include "job/fleet_options.hpp"
#include "job/job.hpp"
#include "pipeline/fleet_merge.hpp"

namespace fleetmerge {

inline constexpr const char* kHtmlReportName = "report.html";

// One map as the page shows it.
struct HtmlReportMap {
  const OccupancyGrid* grid = nullptr;  // any resolution: the page places it by its geometry
  Pose2 T_component_map;                // its map frame in its component's merged frame
  std::string input_path;               // the file it was read from
  int input_width = 0, input_height = 0;
  double input_resolution_m = 0.0;
};

struct HtmlReportComponent {
  std::vector<int> maps;  // indices into HtmlReport::maps; maps[k] has PaletteColour(k)
  const OccupancyGrid* merged = nullptr;  // null for an unmerged map
  std::string preview_file;               // the merged map's colour preview in the folder
};

struct HtmlReport {
  std::string title;
  // report.json's contents (pipeline/report_json.hpp): names, poses, pairs with hypotheses,
  // decisions, timing; the page reads these names. A `pair --out` page uses the same names.
  nlohmann::json report;
  std::vector<HtmlReportMap> maps;
  std::vector<HtmlReportComponent> components;
  nlohmann::json options_changed = nlohmann::json::object();  // key -> {value, default}
  nlohmann::json thresholds = nlohmann::json::object();       // the acceptance rule's numbers
};

// The page of a fleet-merging job (pipeline/job_run.hpp). loaded[m] is job.maps[m] as read;
// merged_files[c] names component c's merged map YAML (its preview is <stem>_preview.png).
HtmlReport HtmlReportOfJob(const Job& job, const std::vector<LoadedMap>& loaded,
                           const FleetResult& result, const nlohmann::json& report,
                           const std::vector<std::string>& merged_files);

// The job's options that differ from FleetOptions' defaults, by job-file key
// ("omega_threshold", "hough.n_theta", ...): {key: {"value": v, "default": d}}.
nlohmann::json ChangedOptions(const FleetOptions& options);

// Writes report.html and the report_map_<m>.png images (on `threads` threads, 0: all cores)
// into `dir`, each atomically (WriteFileAtomically with `mode`) and never over `protect`; returns
// the names written (for the result set's manifest).
std::vector<std::string> WriteHtmlReport(const HtmlReport& page, const std::filesystem::path& dir,
                                         const std::vector<std::filesystem::path>& protect,
                                         int threads = 0, AtomicWrite mode = AtomicWrite::kDurable);

// WriteHtmlReport in two parts, for a caller that has the maps before the report: the images
// depend on the maps alone (maps[m] is the page's maps[m].grid), the page on everything.
// WriteHtmlMapImages then WriteHtmlPage write what WriteHtmlReport writes.
std::vector<std::string> WriteHtmlMapImages(const std::vector<const OccupancyGrid*>& maps,
                                            const std::filesystem::path& dir,
                                            const std::vector<std::filesystem::path>& protect,
                                            int threads = 0,
                                            AtomicWrite mode = AtomicWrite::kDurable);
std::vector<std::string> WriteHtmlPage(const HtmlReport& page, const std::filesystem::path& dir,
                                       const std::vector<std::filesystem::path>& protect,
                                       AtomicWrite mode = AtomicWrite::kDurable);

// The page's HTML text alone (report.html's bytes).
std::string HtmlReportText(const HtmlReport& page);

}  // namespace fleetmerge
