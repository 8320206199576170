#include "pipeline/preview.hpp"

#include <array>

#include "core/parallel.hpp"

namespace fleetmerge {
namespace {

// Weight of the map colour in a free cell's tint: enough to tell robots apart, light enough that
// free space stays clearly lighter than every occupied colour.
constexpr double kFreeTintWeight = 0.2;

// Mean colour of the inputs whose sampled state at (j, i) is `state`; false if there are none.
bool MeanColourOf(const std::vector<cv::Mat1b>& sampled, int j, int i, CellState state,
                  cv::Vec3d& mean_bgr) {
  mean_bgr = cv::Vec3d(0.0, 0.0, 0.0);
  int count = 0;
  for (std::size_t k = 0; k < sampled.size(); ++k) {
    if (sampled[k](j, i) != static_cast<std::uint8_t>(state)) continue;
    const cv::Vec3b colour = PaletteColour(static_cast<int>(k));
    mean_bgr += cv::Vec3d(colour[0], colour[1], colour[2]);
    ++count;
  }
  if (count == 0) return false;
  mean_bgr /= count;
  return true;
}

cv::Vec3b PixelColour(const std::vector<cv::Mat1b>& sampled, int j, int i, CellState merged) {
  cv::Vec3d mean_bgr;
  switch (merged) {
    case CellState::kUnknown:
      return kPreviewUnknown;
    case CellState::kFree:
      if (!MeanColourOf(sampled, j, i, CellState::kFree, mean_bgr)) return kPreviewFree;
      return cv::Vec3d(kPreviewFree) * (1.0 - kFreeTintWeight) + mean_bgr * kFreeTintWeight;
    case CellState::kOccupied:
      if (!MeanColourOf(sampled, j, i, CellState::kOccupied, mean_bgr)) {
        return kPreviewOccupiedByNone;
      }
      return mean_bgr;
  }
  return kPreviewUnknown;
}

}  // namespace

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
  std::vector<cv::Mat1b> sampled(inputs.size());
  ParallelFor(inputs.size(), threads, [&](std::size_t k) {
    sampled[k] = SampleOnto(inputs[k], merged.geometry()).cells();
  });
  const int height = merged.height();
  cv::Mat3b image(height, merged.width());
  ParallelFor(static_cast<std::size_t>(height), threads, [&](std::size_t row) {
    const int j = static_cast<int>(row);
    // Grid rows count up from the bottom, image rows down from the top: flip.
    cv::Vec3b* image_row = image.ptr<cv::Vec3b>(height - 1 - j);
    for (int i = 0; i < merged.width(); ++i) {
      image_row[i] = PixelColour(sampled, j, i, merged.at({i, j}));
    }
  });
  return image;
}

}  // namespace fleetmerge
