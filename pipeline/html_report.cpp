#include "pipeline/html_report.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>

#include "core/error.hpp"
#include "core/image_filters.hpp"
#include "core/parallel.hpp"
#include "io/atomic_file.hpp"
#include "io/png_image.hpp"
#include "pipeline/html_report_template.hpp"
#include "pipeline/preview.hpp"
#include "pipeline/report_json.hpp"

namespace fleetmerge {
namespace {

constexpr const char* kDataMarker = "/*FLEETMERGE_REPORT_DATA*/";

std::string MapImageName(std::size_t m) { return "report_map_" + std::to_string(m) + ".png"; }

bool HasCells(const OccupancyGrid& grid) { return grid.width() > 0 && grid.height() > 0; }

// The map's cells one pixel each, image row 0 at the top (highest y): occupied opaque black,
// free opaque near-white, unknown transparent. The page recolours them per map (screen blend
// keeps black -> the tint, white -> white), so one image serves every colour and hypothesis.
// A palette PNG of these three colours: a quarter of the bytes of RGBA to compress (the
// encoding was 10 % of an 8-robot merge's CPU), the same pixels decoded.
std::string MapImagePng(const OccupancyGrid& grid, int threads) {
  enum : std::uint8_t { kUnknownPixel, kFreePixel, kOccupiedPixel };
  static const std::vector<cv::Vec4b> kPaletteRgba = {
      cv::Vec4b(0, 0, 0, 0), cv::Vec4b(235, 235, 235, 255), cv::Vec4b(0, 0, 0, 255)};
  const int height = grid.height();
  cv::Mat1b image(height, grid.width(), kUnknownPixel);
  for (int j = 0; j < height; ++j) {
    const std::uint8_t* row = grid.cells().ptr<std::uint8_t>(j);
    std::uint8_t* out = image.ptr<std::uint8_t>(height - 1 - j);
    for (int i = 0; i < grid.width(); ++i) {
      if (row[i] == static_cast<std::uint8_t>(CellState::kOccupied)) {
        out[i] = kOccupiedPixel;
      } else if (row[i] == static_cast<std::uint8_t>(CellState::kFree)) {
        out[i] = kFreePixel;
      }
    }
  }
  return EncodeIndexedPng(image, kPaletteRgba, threads);
}

// The box of the grid's known cells: columns [i0, i1) and rows [j0, j1) (rows from the bottom);
// the whole grid when no cell is known.
struct CellBox {
  int i0 = 0, j0 = 0, i1 = 0, j1 = 0;
};
CellBox KnownBox(const OccupancyGrid& grid) {
  // kUnknown is 0, so the bounding box of non-zero cells is that of the known cells (as
  // pipeline/composite.cpp finds it).
  const cv::Rect known = grid.cells().empty() ? cv::Rect() : NonZeroBox(grid.cells());
  if (known.empty()) return {0, 0, grid.width(), grid.height()};
  return {known.x, known.y, known.x + known.width, known.y + known.height};
}

// Centre of the known cells' box `box` in the map frame: where the pose graph draws the map's
// node.
Eigen::Vector2d KnownCentre(const OccupancyGrid& grid, const CellBox& box) {
  const double r = grid.geometry().resolution_m();
  return grid.geometry().T_map_grid() *
         Eigen::Vector2d((box.i0 + box.i1) * r / 2.0, (box.j0 + box.j1) * r / 2.0);
}

nlohmann::json GeometryJson(const OccupancyGrid& grid) {
  return {{"width", grid.width()},
          {"height", grid.height()},
          {"resolution", grid.geometry().resolution_m()},
          {"T_map_grid", PoseJson(grid.geometry().T_map_grid())}};
}

std::string HexColour(const cv::Vec3b& bgr) {
  static const char* kDigits = "0123456789abcdef";
  std::string hex = "#";
  for (int channel : {2, 1, 0}) {
    hex += kDigits[bgr[channel] >> 4];
    hex += kDigits[bgr[channel] & 15];
  }
  return hex;
}

// The page's own data beside report.json's: geometry, images, node positions, inputs, options.
nlohmann::json PageJson(const HtmlReport& page) {
  nlohmann::json maps = nlohmann::json::array();
  std::vector<CellBox> known_boxes;  // of each map, for its image's view and its node
  for (std::size_t m = 0; m < page.maps.size(); ++m) {
    const HtmlReportMap& map = page.maps[m];
    nlohmann::json j = GeometryJson(*map.grid);
    // A grid without cells has no image (an empty PNG cannot be written); the page draws nothing.
    j["image"] = HasCells(*map.grid) ? nlohmann::json(MapImageName(m)) : nlohmann::json();
    j["input"] = {{"path", map.input_path},
                  {"width", map.input_width},
                  {"height", map.input_height},
                  {"resolution", map.input_resolution_m}};
    // The known cells' box in image pixels [u0, v0, u1, v1] (rows from the top): the page fits
    // its views to it rather than to the grid's unknown margins.
    const CellBox box = KnownBox(*map.grid);
    known_boxes.push_back(box);
    j["known_box"] = {box.i0, map.grid->height() - box.j1, box.i1, map.grid->height() - box.j0};
    j["known_cells"] =
        map.grid->width() * map.grid->height() - map.grid->Count(CellState::kUnknown);
    maps.push_back(j);
  }
  nlohmann::json components = nlohmann::json::array();
  for (const HtmlReportComponent& component : page.components) {
    nlohmann::json j = {{"maps", component.maps}, {"colours", nlohmann::json::array()}};
    for (std::size_t k = 0; k < component.maps.size(); ++k) {
      j["colours"].push_back(HexColour(PaletteColour(static_cast<int>(k))));
    }
    if (component.merged) {
      const GridGeometry& g = component.merged->geometry();
      j["merged"] = GeometryJson(*component.merged);
      j["merged"]["image"] = component.preview_file;
      // Node of each map: its known cells' centre in the merged frame, in preview pixels
      // (column, row from the top), as ColourPreview lays the image out.
      j["nodes"] = nlohmann::json::array();
      for (int m : component.maps) {
        const Eigen::Vector2d p_merged =
            page.maps[m].T_component_map * KnownCentre(*page.maps[m].grid, known_boxes[m]);
        const Eigen::Vector2d p_grid = g.T_map_grid().inverse() * p_merged;
        j["nodes"].push_back({{"map", m},
                              {"u", p_grid.x() / g.resolution_m()},
                              {"v", g.height() - p_grid.y() / g.resolution_m()}});
      }
    }
    components.push_back(j);
  }
  return {{"title", page.title},
          {"maps", maps},
          {"components", components},
          {"options_changed", page.options_changed},
          {"thresholds", page.thresholds}};
}

// JSON inside <script>: "</" would end the element early, so it is written "<\/" (the same
// string to a JSON parser).
std::string ScriptSafeJson(const nlohmann::json& data) {
  const std::string text = data.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  std::string out;
  out.reserve(text.size() + 16);
  for (std::size_t k = 0; k < text.size(); ++k) {
    out += text[k];
    if (text[k] == '<' && k + 1 < text.size() && text[k + 1] == '/') out += '\\';
  }
  return out;
}

void AddChanged(nlohmann::json& changed, const std::string& key, const nlohmann::json& value,
                const nlohmann::json& default_value) {
  if (value != default_value) changed[key] = {{"value", value}, {"default", default_value}};
}

}  // namespace

nlohmann::json ChangedOptions(const FleetOptions& o) {
  const FleetOptions d;
  nlohmann::json c = nlohmann::json::object();
  const auto& h = o.pair.hypotheses;
  const auto& hd = d.pair.hypotheses;
  AddChanged(c, "resolution", o.resolution_m, d.resolution_m);
  AddChanged(c, "threads", o.threads, d.threads);
  AddChanged(c, "hypotheses_per_pair", h.max_hypotheses, hd.max_hypotheses);
  AddChanged(c, "omega_threshold", o.omega_threshold, d.omega_threshold);
  AddChanged(c, "min_overlap_cells", o.min_overlap_cells, d.min_overlap_cells);
  AddChanged(c, "min_wall_agreement", o.min_wall_agreement, d.min_wall_agreement);
  AddChanged(c, "min_bridge_wall_agreement", o.min_bridge_wall_agreement,
             d.min_bridge_wall_agreement);
  AddChanged(c, "max_map_cells", o.max_map_cells, d.max_map_cells);
  AddChanged(c, "refine", o.pair.refine, d.pair.refine);
  AddChanged(c, "hough.n_theta", h.hough.n_theta, hd.hough.n_theta);
  AddChanged(c, "hough.rho_step", h.hough.rho_step_cells, hd.hough.rho_step_cells);
  AddChanged(c, "hough.sampling.mode", static_cast<int>(h.hough_sampling.mode),
             static_cast<int>(hd.hough_sampling.mode));
  AddChanged(c, "hough.sampling.fraction", h.hough_sampling.fraction, hd.hough_sampling.fraction);
  AddChanged(c, "hough.sampling.step", h.hough_sampling.step, hd.hough_sampling.step);
  AddChanged(c, "seed", h.hough_sampling.seed, hd.hough_sampling.seed);
  AddChanged(c, "translation.method",
             h.translation.method == TranslationMethod::kXySpectra ? "spectra" : "correlation",
             hd.translation.method == TranslationMethod::kXySpectra ? "spectra" : "correlation");
  AddChanged(c, "translation.sampling.mode", static_cast<int>(h.spectra_sampling.mode),
             static_cast<int>(hd.spectra_sampling.mode));
  AddChanged(c, "translation.sampling.fraction", h.spectra_sampling.fraction,
             hd.spectra_sampling.fraction);
  AddChanged(c, "translation.sampling.step", h.spectra_sampling.step, hd.spectra_sampling.step);
  const auto loss_name = [](RobustLoss loss) {
    return loss == RobustLoss::kNone ? "none" : loss == RobustLoss::kHuber ? "huber" : "cauchy";
  };
  AddChanged(c, "pose_graph.loss", loss_name(o.pose_graph.loss), loss_name(d.pose_graph.loss));
  AddChanged(c, "pose_graph.loss_scale", o.pose_graph.loss_scale, d.pose_graph.loss_scale);
  AddChanged(c, "pose_graph.max_edge_yaw_error_deg",
             o.pose_graph.max_edge_yaw_error_rad * 180.0 / M_PI,
             d.pose_graph.max_edge_yaw_error_rad * 180.0 / M_PI);
  AddChanged(c, "pose_graph.max_edge_translation_error_m",
             o.pose_graph.max_edge_translation_error_m, d.pose_graph.max_edge_translation_error_m);
  const auto fusion_name = [](FusionMode mode) {
    return mode == FusionMode::kMax ? "max" : mode == FusionMode::kVote ? "vote" : "log_odds";
  };
  AddChanged(c, "fusion", fusion_name(o.fusion), fusion_name(d.fusion));
  AddChanged(c, "octree.band_min_m", o.octree.band_min_m, d.octree.band_min_m);
  AddChanged(c, "octree.band_max_m", o.octree.band_max_m, d.octree.band_max_m);
  return c;
}

HtmlReport HtmlReportOfJob(const Job& job, const std::vector<LoadedMap>& loaded,
                           const FleetResult& result, const nlohmann::json& report,
                           const std::vector<std::string>& merged_files) {
  HtmlReport page;
  page.title = job.name;
  page.report = report;
  for (std::size_t m = 0; m < job.maps.size(); ++m) {
    const OccupancyGrid& input = loaded[m].grid;
    page.maps.push_back({&result.maps[m], result.T_component_map[m], job.maps[m].path.string(),
                         input.width(), input.height(), input.geometry().resolution_m()});
  }
  for (std::size_t c = 0; c < result.components.size(); ++c) {
    const FleetComponent& component = result.components[c];
    HtmlReportComponent out{component.maps, nullptr, ""};
    if (component.merged && !merged_files[c].empty()) {
      out.merged = &*component.merged;
      const std::filesystem::path yaml = merged_files[c];
      out.preview_file = yaml.stem().string() + "_preview.png";
    }
    page.components.push_back(out);
  }
  page.options_changed = ChangedOptions(job.options);
  page.thresholds = {{"omega_threshold", job.options.omega_threshold},
                     {"min_overlap_cells", job.options.min_overlap_cells},
                     {"min_wall_agreement", job.options.min_wall_agreement}};
  return page;
}

std::string HtmlReportText(const HtmlReport& page) {
  nlohmann::json data = {{"report", page.report}, {"page", PageJson(page)}};
  std::string html = kHtmlReportTemplate;
  const std::size_t at = html.find(kDataMarker);
  if (at == std::string::npos) throw Error("internal: report.html template has no data marker");
  html.replace(at, std::string(kDataMarker).size(), ScriptSafeJson(data));
  return html;
}

std::vector<std::string> WriteHtmlMapImages(const std::vector<const OccupancyGrid*>& maps,
                                            const std::filesystem::path& dir,
                                            const std::vector<std::filesystem::path>& protect,
                                            int threads, AtomicWrite mode) {
  std::vector<std::string> written;
  for (std::size_t m = 0; m < maps.size(); ++m) {
    if (!maps[m]) throw Error("internal: report.html map " + std::to_string(m) + " unset");
    if (HasCells(*maps[m])) written.push_back(MapImageName(m));
  }
  // On threads: each atomic write waits for its fsync (about 8 ms a file measured here), and the
  // waits overlap.
  ParallelFor(maps.size(), threads, [&](std::size_t m) {
    if (!HasCells(*maps[m])) return;
    // A site's map (16 M cells) is deflated in bands on the threads the smaller maps left.
    WriteFileAtomically(dir / MapImageName(m), MapImagePng(*maps[m], threads), protect, mode);
  });
  return written;
}

std::vector<std::string> WriteHtmlPage(const HtmlReport& page, const std::filesystem::path& dir,
                                       const std::vector<std::filesystem::path>& protect,
                                       AtomicWrite mode) {
  WriteFileAtomically(dir / kHtmlReportName, HtmlReportText(page), protect, mode);
  return {kHtmlReportName};
}

std::vector<std::string> WriteHtmlReport(const HtmlReport& page, const std::filesystem::path& dir,
                                         const std::vector<std::filesystem::path>& protect,
                                         int threads, AtomicWrite mode) {
  std::vector<const OccupancyGrid*> maps;
  for (const HtmlReportMap& map : page.maps) maps.push_back(map.grid);
  std::vector<std::string> written = WriteHtmlMapImages(maps, dir, protect, threads, mode);
  for (std::string& name : WriteHtmlPage(page, dir, protect, mode)) written.push_back(name);
  return written;
}

}  // namespace fleetmerge
