#include "pipeline/preview.hpp"

#include <array>

#include "core/parallel.hpp"

namespace fleetmerge {
namespace {

// Weight of the map colour in a free cell's tint: enough to tell robots apart, light enough that
// free space stays clearly lighter than every occupied colour.
constexpr double kFreeTintWeight = 0.2;

// One band of preview rows: per cell, the sum of the colours of the inputs that see it free
// (occupied) and how many do. Colours are integers, so the sums are exact in any order.
struct BandColours {
  explicit BandColours(const cv::Rect& band)
      : band(band),
        free_sum(band.height, band.width, cv::Vec3i(0, 0, 0)),
        occupied_sum(band.height, band.width, cv::Vec3i(0, 0, 0)),
        free_count(band.height, band.width, 0),
        occupied_count(band.height, band.width, 0) {}

  void Add(const cv::Mat1b& sampled, const cv::Rect& region, const cv::Vec3i& colour) {
    // Row pointers, not Mat_::operator() per cell: the colouring was ~8 % of a cached re-run's CPU.
    for (int j = region.y; j < region.y + region.height; ++j) {
      const std::uint8_t* states = sampled.ptr<std::uint8_t>(j);
      const int r = j - band.y;
      cv::Vec3i* free_sum_row = free_sum.ptr<cv::Vec3i>(r);
      cv::Vec3i* occupied_sum_row = occupied_sum.ptr<cv::Vec3i>(r);
      int* free_count_row = free_count.ptr<int>(r);
      int* occupied_count_row = occupied_count.ptr<int>(r);
      for (int i = region.x; i < region.x + region.width; ++i) {
        if (states[i] == static_cast<std::uint8_t>(CellState::kFree)) {
          free_sum_row[i] += colour;
          ++free_count_row[i];
        } else if (states[i] == static_cast<std::uint8_t>(CellState::kOccupied)) {
          occupied_sum_row[i] += colour;
          ++occupied_count_row[i];
        }
      }
    }
  }

  // The pixel of merged cell (i, j) of the band, in state `merged`.
  cv::Vec3b Pixel(int j, int i, CellState merged) const {
    const int r = j - band.y;
    switch (merged) {
      case CellState::kUnknown:
        return kPreviewUnknown;
      // Most cells are seen by one map: its colour is the mean, with no division to make.
      case CellState::kFree: {
        const int count = free_count(r, i);
        if (count == 0) return kPreviewFree;
        const cv::Vec3d sum_bgr(free_sum(r, i));
        const cv::Vec3d mean_bgr = count == 1 ? sum_bgr : sum_bgr / count;
        return cv::Vec3d(kPreviewFree) * (1.0 - kFreeTintWeight) + mean_bgr * kFreeTintWeight;
      }
      case CellState::kOccupied: {
        const int count = occupied_count(r, i);
        if (count == 0) return kPreviewOccupiedByNone;
        if (count == 1) return cv::Vec3b(occupied_sum(r, i));
        return cv::Vec3d(occupied_sum(r, i)) / count;
      }
    }
    return kPreviewUnknown;
  }

  cv::Rect band;
  cv::Mat_<cv::Vec3i> free_sum, occupied_sum;
  cv::Mat1i free_count, occupied_count;
};

// The band's rows of the preview image (row 0 at the top).
void ColourRows(const BandColours& colours, const OccupancyGrid& merged, cv::Mat3b& image) {
  const int height = merged.height(), width = merged.width();
  for (int j = colours.band.y; j < colours.band.y + colours.band.height; ++j) {
    // Grid rows count up from the bottom, image rows down from the top: flip.
    cv::Vec3b* image_row = image.ptr<cv::Vec3b>(height - 1 - j);
    const std::uint8_t* states = merged.cells().ptr<std::uint8_t>(j);
    const int r = j - colours.band.y;
    const cv::Vec3i* free_sum = colours.free_sum.ptr<cv::Vec3i>(r);
    const cv::Vec3i* occupied_sum = colours.occupied_sum.ptr<cv::Vec3i>(r);
    const int* free_count = colours.free_count.ptr<int>(r);
    const int* occupied_count = colours.occupied_count.ptr<int>(r);
    // A map's cells come in runs along a row: the last known cell's pixel is reused while its
    // state, sums and counts repeat (Pixel's doubles per cell were a quarter of the colouring).
    std::uint8_t last_state = 0xff;
    cv::Vec3i last_sum;
    int last_count = -1;
    cv::Vec3b last_pixel;
    for (int i = 0; i < width; ++i) {
      const std::uint8_t state = states[i];
      if (state == static_cast<std::uint8_t>(CellState::kUnknown)) {
        image_row[i] = kPreviewUnknown;
        continue;
      }
      const bool free = state == static_cast<std::uint8_t>(CellState::kFree);
      const cv::Vec3i& sum = free ? free_sum[i] : occupied_sum[i];
      const int count = free ? free_count[i] : occupied_count[i];
      if (state != last_state || count != last_count || sum != last_sum) {
        last_state = state;
        last_count = count;
        last_sum = sum;
        last_pixel = colours.Pixel(j, i, static_cast<CellState>(state));
      }
      image_row[i] = last_pixel;
    }
  }
}

class PreviewBand : public CompositeObserver::Band {
 public:
  PreviewBand(const cv::Rect& band, cv::Mat3b& image) : colours_(band), image_(image) {}
  void Add(std::size_t k, const cv::Mat1b& sampled, const cv::Rect& region) override {
    colours_.Add(sampled, region, cv::Vec3i(PaletteColour(static_cast<int>(k))));
  }
  void Finish(const OccupancyGrid& merged) override { ColourRows(colours_, merged, image_); }

 private:
  BandColours colours_;
  cv::Mat3b& image_;  // each band writes its own rows
};

}  // namespace

void PreviewColourer::Begin(const GridGeometry& merged) {
  image_.create(merged.height(), merged.width());
}

std::unique_ptr<CompositeObserver::Band> PreviewColourer::StartBand(const cv::Rect& band) {
  return std::make_unique<PreviewBand>(band, image_);
}

cv::Vec3b PaletteColour(int input_index) {
  // RGB values written as usually listed, stored here BGR.
  static const std::array<cv::Vec3b, 10> kPaletteBgr = {
      cv::Vec3b(180, 119, 31),  cv::Vec3b(14, 127, 255),  cv::Vec3b(44, 160, 44),
      cv::Vec3b(40, 39, 214),   cv::Vec3b(189, 103, 148), cv::Vec3b(75, 86, 140),
      cv::Vec3b(194, 119, 227), cv::Vec3b(110, 20, 20),   cv::Vec3b(34, 189, 188),
      cv::Vec3b(207, 190, 23)};
  const int n = static_cast<int>(kPaletteBgr.size());
  return kPaletteBgr[((input_index % n) + n) % n];
}

cv::Mat3b ColourPreview(const std::vector<CompositeInput>& inputs, const OccupancyGrid& merged,
                        int threads) {
  const InputSampler sampler(inputs, merged.geometry());
  const int height = merged.height(), width = merged.width();
  cv::Mat3b image(height, width);
  cv::Mat1b sampled(height, width);  // scratch; each band touches its own rows
  // Bands of rows, each coloured from the inputs that reach it: the inputs are sampled over
  // what they cover only, so memory does not grow with maps x merged cells.
  constexpr int kBandRows = 64;
  const int bands = (height + kBandRows - 1) / kBandRows;
  ParallelFor(static_cast<std::size_t>(bands), threads, [&](std::size_t band_index) {
    const int y0 = static_cast<int>(band_index) * kBandRows;
    BandColours colours(cv::Rect(0, y0, width, std::min(kBandRows, height - y0)));
    for (std::size_t k = 0; k < inputs.size(); ++k) {
      const cv::Rect region = sampler.Sample(k, colours.band, sampled);
      if (region.area() > 0) {
        colours.Add(sampled, region, cv::Vec3i(PaletteColour(static_cast<int>(k))));
      }
    }
    ColourRows(colours, merged, image);
  });
  return image;
}

}  // namespace fleetmerge
