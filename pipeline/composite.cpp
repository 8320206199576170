#include "pipeline/composite.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

#include "core/error.hpp"
#include "core/image_filters.hpp"
#include "core/parallel.hpp"

namespace fleetmerge {
namespace {

// Sizes come from metric ratios such as 0.5 / 0.1 = 5.000000000000001; the slack keeps them from
// rounding up to an extra cell.
constexpr double kIndexSlack = 1e-9;

using CellAffine = InputSampler::CellAffine;

// Pose of the target grid frame in the input's grid frame:
//   T_ingrid_targetgrid = T_ingrid_inmap * T_inmap_merged * T_merged_targetgrid.
Pose2 InputGridFromTargetGrid(const CompositeInput& input, const GridGeometry& target) {
  return input.grid->geometry().T_map_grid().inverse() * input.T_merged_map.inverse() *
         target.T_map_grid();
}

CellAffine TargetToInputCells(const CompositeInput& input, const GridGeometry& target) {
  const Pose2 T_in_target = InputGridFromTargetGrid(input, target);
  const double input_resolution_m = input.grid->geometry().resolution_m();
  // Target cell (i, j) has its centre at ((i, j) + 0.5) * R in the target grid frame; dividing
  // the input-grid point by r turns metres into input cells.
  const Eigen::Matrix2d A = T_in_target.rotation() * (target.resolution_m() / input_resolution_m);
  CellAffine affine;
  affine.step_i = A.col(0);
  affine.step_j = A.col(1);
  affine.origin = T_in_target.translation_m() / input_resolution_m + 0.5 * (A.col(0) + A.col(1));
  return affine;
}

// Target cells whose centres can fall inside the input grid: the input rectangle's bounding box
// in target cells, widened by a cell against rounding, clipped to the target.
cv::Rect TargetRegionOfInput(const CompositeInput& input, const GridGeometry& target) {
  const GridGeometry& in = input.grid->geometry();
  const Pose2 T_target_in = InputGridFromTargetGrid(input, target).inverse();
  Eigen::Array2d lo = Eigen::Array2d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Array2d hi = -lo;
  for (const double fx : {0.0, 1.0}) {
    for (const double fy : {0.0, 1.0}) {
      const Eigen::Vector2d corner_in(fx * in.width() * in.resolution_m(),
                                      fy * in.height() * in.resolution_m());
      const Eigen::Array2d c = (T_target_in * corner_in).array() / target.resolution_m();
      lo = lo.min(c);
      hi = hi.max(c);
    }
  }
  const int x0 = std::max(0, static_cast<int>(std::floor(lo.x())) - 1);
  const int y0 = std::max(0, static_cast<int>(std::floor(lo.y())) - 1);
  const int x1 = std::min(target.width(), static_cast<int>(std::ceil(hi.x())) + 1);
  const int y1 = std::min(target.height(), static_cast<int>(std::ceil(hi.y())) + 1);
  return cv::Rect(x0, y0, std::max(0, x1 - x0), std::max(0, y1 - y0));
}

// Narrows [*begin, *end) to the i with 0 <= start + i * step < limit, give or take a cell.
void ClipRowToInput(double start, double step, double limit, int* begin, int* end) {
  if (step == 0.0) {
    if (!(start >= 0.0 && start < limit)) *end = *begin;
    return;
  }
  const double i0 = -start / step, i1 = (limit - start) / step;  // the range's ends, any order
  const double lo = std::floor(std::min(i0, i1)) - 1.0, hi = std::ceil(std::max(i0, i1)) + 1.0;
  if (lo > *begin) *begin = lo >= *end ? *end : static_cast<int>(lo);
  if (hi < *end) *end = hi <= *begin ? *begin : static_cast<int>(hi);
}

// Writes the input's state at each target cell centre of `region` into `out` (target-sized);
// cells of the region outside the input are left as they are.
void SampleRegion(const CompositeInput& input, const CellAffine& affine, const cv::Rect& region,
                  cv::Mat1b& out) {
  const cv::Mat1b& cells = input.grid->cells();
  const double width = cells.cols;
  const double height = cells.rows;
  for (int j = region.y; j < region.y + region.height; ++j) {
    const Eigen::Vector2d row_start = affine.origin + j * affine.step_j;
    std::uint8_t* out_row = out.ptr<std::uint8_t>(j);
    // The row's cells whose centres can land inside the input, widened by a cell against
    // rounding (the test below still decides each cell): a rotated input fills about half of
    // its bounding box.
    int i_begin = region.x, i_end = region.x + region.width;
    ClipRowToInput(row_start.x(), affine.step_i.x(), width, &i_begin, &i_end);
    ClipRowToInput(row_start.y(), affine.step_i.y(), height, &i_begin, &i_end);
    // u = row_start + i * step_i, not a running sum: no drift along long rows.
    const auto u_of = [&](int i) -> Eigen::Vector2d {
      return {row_start.x() + i * affine.step_i.x(), row_start.y() + i * affine.step_i.y()};
    };
    const auto inside = [&](const Eigen::Vector2d& u) {
      return u.x() >= 0.0 && u.y() >= 0.0 && u.x() < width && u.y() < height;
    };
    // Each coordinate is monotonic in i (so is each rounding step of its sum), so the centres
    // inside the input are one run of i: trim the widened ends to it, then the loop needs no
    // test, and with u >= 0 the int cast equals floor. The clamp only guards the reads should a
    // compiler evaluate u differently here and in `inside` (a fused multiply-add in one only).
    while (i_begin < i_end && !inside(u_of(i_begin))) ++i_begin;
    while (i_end > i_begin && !inside(u_of(i_end - 1))) --i_end;
    const int last_col = cells.cols - 1, last_row = cells.rows - 1;
    for (int i = i_begin; i < i_end; ++i) {
      const Eigen::Vector2d u = u_of(i);
      out_row[i] = cells(std::min(static_cast<int>(u.y()), last_row),
                         std::min(static_cast<int>(u.x()), last_col));
    }
  }
}

void ValidateInputs(const std::vector<CompositeInput>& inputs, double resolution_m,
                    int reference_input) {
  if (!(resolution_m > 0.0) || !std::isfinite(resolution_m)) {
    std::ostringstream msg;
    msg << "composite: merged resolution must be a finite number > 0 m, got " << resolution_m;
    throw Error(msg.str());
  }
  if (inputs.size() > std::numeric_limits<std::uint16_t>::max()) {
    throw Error("composite: at most 65535 input maps (per-cell counts are 16-bit)");
  }
  for (std::size_t k = 0; k < inputs.size(); ++k) {
    if (inputs[k].grid == nullptr) {
      throw Error("composite: input " + std::to_string(k) + " has no grid (null pointer)");
    }
  }
  if (reference_input < -1 || reference_input >= static_cast<int>(inputs.size())) {
    throw Error("composite: reference input " + std::to_string(reference_input) +
                " is not -1 or one of the " + std::to_string(inputs.size()) + " inputs");
  }
}

// The merged grid frame's pose in the merged frame before it is moved to the known cells: the
// reference grid's frame, or the merged frame itself.
Pose2 LatticeFrame(const std::vector<CompositeInput>& inputs, int reference_input) {
  if (reference_input < 0) return Pose2();
  const CompositeInput& reference = inputs[static_cast<std::size_t>(reference_input)];
  return reference.T_merged_map * reference.grid->geometry().T_map_grid();
}

// The merged geometry around all known cells plus a one-cell margin, on the lattice of whole
// cells from LatticeFrame; a 0 x 0 geometry when no input has a known cell. Without a reference
// the corner is not snapped to the lattice (an input at identity pose and the same resolution
// keeps its cell boundaries only if it has the lowest corner); with one it is, so the reference
// always keeps them.
GridGeometry MergedGeometry(const std::vector<CompositeInput>& inputs, double resolution_m,
                            int reference_input, std::int64_t max_cells) {
  const Pose2 T_merged_lattice = LatticeFrame(inputs, reference_input);
  const Pose2 T_lattice_merged = T_merged_lattice.inverse();
  Eigen::Array2d lo = Eigen::Array2d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Array2d hi = -lo;
  for (const CompositeInput& input : inputs) {
    if (input.grid->cells().empty()) continue;
    // kUnknown is 0, so the bounding box of non-zero cells is that of the known cells.
    const cv::Rect known = NonZeroBox(input.grid->cells());
    if (known.area() == 0) continue;
    const GridGeometry& g = input.grid->geometry();
    const Pose2 T_lattice_grid = T_lattice_merged * input.T_merged_map * g.T_map_grid();
    for (const int x : {known.x, known.x + known.width}) {
      for (const int y : {known.y, known.y + known.height}) {
        const Eigen::Array2d c =
            (T_lattice_grid * (Eigen::Vector2d(x, y) * g.resolution_m())).array();
        lo = lo.min(c);
        hi = hi.max(c);
      }
    }
  }
  if (!(lo <= hi).all()) return GridGeometry(resolution_m, {0, 0}, T_merged_lattice);
  // Poses far apart (a fixed pose or initial_pose kilometres off) would ask for a grid of
  // billions of cells, or overflow int: refused before any allocation, in double.
  const Eigen::Array2d extent_cells = (hi - lo) / resolution_m + 3.0;
  if (!(extent_cells.x() * extent_cells.y() <= static_cast<double>(max_cells)) ||
      !(extent_cells.maxCoeff() < std::numeric_limits<int>::max())) {
    std::ostringstream what;
    what << std::fixed << std::setprecision(0) << "the merged map would be " << extent_cells.x()
         << " x " << extent_cells.y() << " cells (" << (hi - lo).x() << " x " << (hi - lo).y()
         << " m at " << std::setprecision(3) << resolution_m << " m), more than the limit of "
         << max_cells
         << " cells: its maps' poses are that far apart (check fixed poses and initial_poses, "
            "or raise max_map_cells)";
    throw Error(what.str());
  }
  if (reference_input < 0) {
    const Eigen::Array2d origin_m = lo - resolution_m;
    const Eigen::Array2d cells = (hi - lo) / resolution_m + 2.0;  // + margin on both sides
    const Eigen::Array2i size(static_cast<int>(std::ceil(cells.x() - kIndexSlack)),
                              static_cast<int>(std::ceil(cells.y() - kIndexSlack)));
    return GridGeometry(resolution_m, size, Pose2(origin_m.matrix(), 0.0));
  }
  // Whole lattice cells from the one holding lo to the one holding hi, plus the margin. The
  // reference's own corners sit on the lattice; the slack keeps 12.000000000001 from adding a
  // cell (it would only widen the margin).
  const Eigen::Array2d lo_cells = (lo / resolution_m + kIndexSlack).floor() - 1.0;
  const Eigen::Array2d hi_cells = (hi / resolution_m - kIndexSlack).ceil() + 1.0;
  const Eigen::Array2i size = (hi_cells - lo_cells).cast<int>();
  return GridGeometry(resolution_m, size,
                      T_merged_lattice * Pose2((lo_cells * resolution_m).matrix(), 0.0));
}

}  // namespace

CellState Fuse(int occupied_count, int free_count, FusionMode mode) {
  if (occupied_count == 0 && free_count == 0) return CellState::kUnknown;
  bool occupied = false;
  switch (mode) {
    case FusionMode::kLogOdds:
      occupied = occupied_count * kLogOddsOccupied + free_count * kLogOddsFree >= 0.0;
      break;
    case FusionMode::kMax:
      occupied = occupied_count > 0;
      break;
    case FusionMode::kVote:
      occupied = occupied_count >= free_count;
      break;
  }
  return occupied ? CellState::kOccupied : CellState::kFree;
}

InputSampler::InputSampler(const std::vector<CompositeInput>& inputs, const GridGeometry& target)
    : inputs_(inputs) {
  for (const CompositeInput& input : inputs) {
    if (input.grid == nullptr) throw Error("InputSampler: an input has no grid (null pointer)");
    affines_.push_back(TargetToInputCells(input, target));
    regions_.push_back(TargetRegionOfInput(input, target));
  }
}

cv::Rect InputSampler::Sample(std::size_t k, const cv::Rect& band, cv::Mat1b& scratch) const {
  const cv::Rect region = regions_[k] & band;
  if (region.area() == 0) return cv::Rect();
  scratch(region).setTo(static_cast<std::uint8_t>(CellState::kUnknown));
  SampleRegion(inputs_[k], affines_[k], region, scratch);
  return region;
}

OccupancyGrid SampleOnto(const CompositeInput& input, const GridGeometry& target) {
  if (input.grid == nullptr) throw Error("SampleOnto: the input has no grid (null pointer)");
  OccupancyGrid out(target);
  SampleRegion(input, TargetToInputCells(input, target), TargetRegionOfInput(input, target),
               out.mutable_cells());
  return out;
}

OccupancyGrid Composite(const std::vector<CompositeInput>& inputs, double resolution_m,
                        FusionMode mode, int threads, int reference_input,
                        CompositeObserver* observer, std::int64_t max_cells) {
  ValidateInputs(inputs, resolution_m, reference_input);
  const GridGeometry geometry = MergedGeometry(inputs, resolution_m, reference_input, max_cells);
  if (observer != nullptr) observer->Begin(geometry);
  const cv::Size size(geometry.width(), geometry.height());
  const InputSampler sampler(inputs, geometry);
  OccupancyGrid merged(geometry);
  cv::Mat1b sampled(size);  // scratch; only each input's region is touched
  const bool any_fixed = std::any_of(inputs.begin(), inputs.end(),
                                     [](const CompositeInput& input) { return input.fixed; });
  // Each band of rows is fused from every input's part in it; the bands touch disjoint rows.
  // The counts are the band's own (two 64-row buffers per band, not two merged-size arrays
  // zeroed on one thread before the bands start).
  constexpr int kBandRows = 64;
  const int bands = (size.height + kBandRows - 1) / kBandRows;
  ParallelFor(static_cast<std::size_t>(bands), threads, [&](std::size_t band_index) {
    const int y0 = static_cast<int>(band_index) * kBandRows;
    const cv::Rect band(0, y0, size.width, std::min(kBandRows, size.height - y0));
    const std::unique_ptr<CompositeObserver::Band> seen =
        observer != nullptr ? observer->StartBand(band) : nullptr;
    // Counts of the maps that move, and (only with fixed inputs) of the fixed ones apart.
    cv::Mat1w occupied_count(band.height, band.width, std::uint16_t{0});
    cv::Mat1w free_count(band.height, band.width, std::uint16_t{0});
    cv::Mat1w fixed_occupied_count, fixed_free_count;
    if (any_fixed) {
      fixed_occupied_count = cv::Mat1w(band.height, band.width, std::uint16_t{0});
      fixed_free_count = cv::Mat1w(band.height, band.width, std::uint16_t{0});
    }
    for (std::size_t k = 0; k < inputs.size(); ++k) {
      const cv::Rect region = sampler.Sample(k, band, sampled);
      if (seen && region.area() > 0) seen->Add(k, sampled, region);
      cv::Mat1w& occupied = inputs[k].fixed ? fixed_occupied_count : occupied_count;
      cv::Mat1w& free = inputs[k].fixed ? fixed_free_count : free_count;
      // One pass over the region counts both states (masked cv::add calls would take five passes
      // and two mask allocations per input and band).
      for (int j = region.y; j < region.y + region.height; ++j) {
        const std::uint8_t* states = sampled.ptr<std::uint8_t>(j);
        std::uint16_t* occupied_row = occupied.ptr<std::uint16_t>(j - band.y);
        std::uint16_t* free_row = free.ptr<std::uint16_t>(j - band.y);
        for (int i = region.x; i < region.x + region.width; ++i) {
          occupied_row[i] += states[i] == static_cast<std::uint8_t>(CellState::kOccupied);
          free_row[i] += states[i] == static_cast<std::uint8_t>(CellState::kFree);
        }
      }
    }
    for (int j = band.y; j < band.y + band.height; ++j) {
      const std::uint16_t* occupied_row = occupied_count.ptr<std::uint16_t>(j - band.y);
      const std::uint16_t* free_row = free_count.ptr<std::uint16_t>(j - band.y);
      std::uint8_t* merged_row = merged.mutable_cells().ptr<std::uint8_t>(j);
      for (int i = 0; i < size.width; ++i) {
        merged_row[i] = static_cast<std::uint8_t>(Fuse(occupied_row[i], free_row[i], mode));
      }
      if (!any_fixed) continue;
      const std::uint16_t* fixed_occupied_row = fixed_occupied_count.ptr<std::uint16_t>(j - band.y);
      const std::uint16_t* fixed_free_row = fixed_free_count.ptr<std::uint16_t>(j - band.y);
      for (int i = 0; i < size.width; ++i) {
        // Where no fixed map knows the cell, the moving maps' fusion above stands.
        if (fixed_occupied_row[i] == 0 && fixed_free_row[i] == 0) continue;
        merged_row[i] =
            static_cast<std::uint8_t>(Fuse(fixed_occupied_row[i], fixed_free_row[i], mode));
      }
    }
    if (seen) seen->Finish(merged);
  });
  return merged;
}

}  // namespace fleetmerge
