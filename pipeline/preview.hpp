// A colour picture of a merged map that shows which robot saw what.
//
// Unknown cells are mid grey, free cells near-white tinted by the colour(s) of the maps that see
// them free, occupied cells in the colour of the map(s) that see them occupied (the mean colour
// when several do, so overlaps read as mixtures). Map k gets PaletteColour(k).
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "core/occupancy_grid.hpp"
#include "pipeline/composite.hpp"

namespace fleetmerge {

// Ten colours (Tableau 10 with its grey swapped for navy, which the unknown grey would hide),
// cycling for k >= 10. BGR order, as cv::imwrite expects.
cv::Vec3b PaletteColour(int input_index);

// The colours used for cell states in the preview.
inline const cv::Vec3b kPreviewUnknown(128, 128, 128);
inline const cv::Vec3b kPreviewFree(245, 245, 245);      // before tinting
inline const cv::Vec3b kPreviewOccupiedByNone(0, 0, 0);  // occupied in `merged`, by no input

// An image of `merged` (as made by Composite from `inputs`) with image row 0 at the TOP (highest
// y), ready for cv::imwrite: the grid's row j is image row height - 1 - j. The category of each
// pixel (unknown / free / occupied) comes from `merged`; the colours from the inputs.
// The inputs are sampled, and the rows coloured, on `threads` threads (<= 0: all cores).
cv::Mat3b ColourPreview(const std::vector<CompositeInput>& inputs, const OccupancyGrid& merged,
                        int threads = 1);

// ColourPreview made while Composite fuses (pass it as Composite's observer): image() is then
// ColourPreview(inputs, merged) pixel for pixel, without sampling the inputs a second time
// (BM_CompositeAndPreview: docs/speed.md).
class PreviewColourer : public CompositeObserver {
 public:
  void Begin(const GridGeometry& merged) override;
  std::unique_ptr<Band> StartBand(const cv::Rect& band) override;
  const cv::Mat3b& image() const { return image_; }

 private:
  cv::Mat3b image_;
};

}  // namespace fleetmerge
