// Compositing several occupancy grids, each placed by a pose in a common "merged" frame, into one
// merged grid.
//
// The merged grid covers the bounding box of every input's known cells, transformed into the
// merged frame, plus one cell of unknown margin on each side. With a reference input (the map
// whose frame is the merged frame) its cells are the reference grid's cells, extended by whole
// cells: same orientation, same cell boundaries, so at the reference's resolution a cell that
// only the reference knows comes out exactly as it is (users navigate in that map). Without one
// the merged grid is axis-aligned in the merged frame with its corner at the known cells' corner.
// Each merged cell centre is carried back into every input map by the inverse pose and takes that
// map's nearest cell (the cell containing the point, as GridGeometry::CellOf does). Pulling from
// the inputs this way, rather than pushing input cells forward, leaves no holes when a map is
// rotated or has finer cells. Nearest-cell lookup can drop one-cell walls when the merged cells are
// coarser than an input's: resample such inputs first with ResampleToResolution
// (core/resample.hpp), which keeps them.
//
// Fusion of the per-map states of one merged cell (unknown never votes; a cell no map knows
// stays kUnknown in every mode):
//   kLogOdds  L = n_occ * l_occ + n_free * l_free with l_occ = logit(0.7) = +0.847 and
//             l_free = logit(0.4) = -0.405, the hit/miss probabilities of OctoMap's default
//             sensor model (Hornung et al., Autonomous Robots 2013). kOccupied if L > 0, kFree if
//             L < 0. One "occupied" outweighs two "free" but not three: a wall seen by one robot
//             survives a couple of robots that saw through it (glass, a door since opened).
//             The threshold is 0: any net evidence decides. An exact tie L = 0 is impossible
//             (it needs (7/3)^n_occ = (3/2)^n_free); a rounding tie counts as kOccupied
//             (conservative, as in kVote).
//   kMax      kOccupied if any map says occupied, else kFree: conservative for navigation.
//   kVote     majority of the known states; a tie is kOccupied (conservative).
// Fixed inputs (CompositeInput::fixed, a site's base map) are kept: a cell that any fixed input
// knows is fused from the fixed inputs alone, by the same rule, and the other maps fill only the
// cells no fixed input knows. A site takes yesterday's merged map as today's base; were the
// robots' cells fused into it, each day's robots would thicken its walls by their own rounding
// of the walls onto its cells (a cell here and there), and the site map would drift day by day.
#pragma once

#include <cstdint>
#include <memory>
#include <opencv2/core.hpp>
#include <vector>

#include "core/grid_geometry.hpp"
#include "core/occupancy_grid.hpp"
#include "core/pose2.hpp"
#include "job/fusion_mode.hpp"

namespace fleetmerge {

// Log-odds evidence of one map's occupied / free cell in FusionMode::kLogOdds.
inline constexpr double kLogOddsOccupied = 0.84729786038720367;  // log(0.7 / 0.3)
inline constexpr double kLogOddsFree = -0.40546510810816438;     // log(0.4 / 0.6)

struct CompositeInput {
  const OccupancyGrid* grid = nullptr;  // not owned; must outlive the call
  Pose2 T_merged_map;                   // pose of this map's own map frame in the merged frame
  // A fixed (base) map: where a fixed input knows a cell, the fixed inputs alone decide it.
  bool fixed = false;
};

// Sees what Composite samples, for work that needs each input's states at the merged cells as
// well as the fused cells (the preview's colours, pipeline/preview.hpp): the inputs are then
// sampled once for both.
class CompositeObserver {
 public:
  // One band of merged rows. Bands run on Composite's threads, each band on one thread.
  class Band {
   public:
    virtual ~Band() = default;
    // Input k's states over `region`, a part of the band, in `sampled` (merged-sized).
    virtual void Add(std::size_t k, const cv::Mat1b& sampled, const cv::Rect& region) = 0;
    // After every input: the band's rows of `merged` are fused.
    virtual void Finish(const OccupancyGrid& merged) = 0;
  };
  virtual ~CompositeObserver() = default;
  // Before any band: the merged grid's geometry.
  virtual void Begin(const GridGeometry& merged) = 0;
  virtual std::unique_ptr<Band> StartBand(const cv::Rect& band) = 0;
};

// The merged grid at resolution_m. With no known cell in any input it is an empty (0 x 0) grid.
// `reference_input` indexes `inputs` (-1: none): the merged cells are on its cell lattice.
// Throws fleetmerge::Error unless resolution_m is a finite number > 0, every grid is set and
// reference_input is -1 or an index. Bands of merged rows are fused on `threads` threads (<= 0:
// all cores): the same grid for any count. `observer`, when set, sees every band's samples.
// Throws fleetmerge::Error, before allocating, when the merged grid would exceed max_cells.
OccupancyGrid Composite(const std::vector<CompositeInput>& inputs, double resolution_m,
                        FusionMode mode = FusionMode::kLogOdds, int threads = 1,
                        int reference_input = -1, CompositeObserver* observer = nullptr,
                        std::int64_t max_cells = kDefaultMaxMapCells);

// One input's state at the centre of every cell of `target` (whose map frame is the merged
// frame): the lookup Composite fuses, also used to colour previews. kUnknown where the centre
// falls outside the input grid.
OccupancyGrid SampleOnto(const CompositeInput& input, const GridGeometry& target);

// The inputs' states at the cell centres of `target`, one band of rows at a time: what Composite
// fuses and ColourPreview colours. Only the cells an input can reach are sampled, so a fleet of
// many maps costs what its maps cover, not maps x target cells.
class InputSampler {
 public:
  // Keeps a reference to `inputs` (every grid set), which must outlive the sampler.
  InputSampler(const std::vector<CompositeInput>& inputs, const GridGeometry& target);

  // Writes input k's state at each cell centre of the returned part of `band` (target cells)
  // into `scratch` (target-sized; kUnknown where the centre falls outside the input grid) and
  // returns that part: empty when the input cannot reach the band. Other cells of `scratch` are
  // left as they are, so threads may sample disjoint bands into one scratch.
  cv::Rect Sample(std::size_t k, const cv::Rect& band, cv::Mat1b& scratch) const;

  // Continuous cell coordinates u in an input grid of the centre of target cell (i, j):
  //   u = origin + i * step_i + j * step_j.
  // A rigid motion of a regular grid is affine in the cell indices, so the inner loop needs only
  // multiply-adds, no trigonometry and no pose composition per cell.
  struct CellAffine {
    Eigen::Vector2d origin;
    Eigen::Vector2d step_i;
    Eigen::Vector2d step_j;
  };

 private:
  const std::vector<CompositeInput>& inputs_;
  std::vector<CellAffine> affines_;  // target cells -> input k's cells
  std::vector<cv::Rect> regions_;    // target cells whose centres can fall inside input k
};

// The fusion rule above for one merged cell, given how many maps see it occupied and free.
CellState Fuse(int occupied_count, int free_count, FusionMode mode);

}  // namespace fleetmerge
