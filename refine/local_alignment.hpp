// Local refinement of a pairwise hypothesis to sub-degree, sub-cell accuracy (beyond the paper).
//
// The Hough steps quantise rotation to 180/n_theta degrees and the coarse correlation translation
// to a few cells. Starting there, we minimise over T = T_ga_gb (cells)
//   sum_p rho( D_a(T p) )  +  sum_q rho( D_b(T^-1 q) )
// where p are b's wall cells, q are a's wall cells, D_x is x's truncated wall distance field and
// rho a Cauchy loss: a symmetric, robust chamfer alignment solved by Levenberg-Marquardt (Ceres'
// TinySolver).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "core/occupancy_grid.hpp"
#include "core/pose2.hpp"
#include "refine/wall_distance_field.hpp"

namespace fleetmerge {

struct LocalAlignmentOptions {
  int max_points = 1000;  // wall cells used per map (every k-th), bounds the cost
  int max_iterations = 20;
  double loss_scale_cells = 1.0;  // Cauchy scale: residuals beyond ~1 cell are outliers
  // Levenberg-Marquardt stops when a step lowers the cost by less than this share of it.
  double function_tolerance = 1e-6;
};

// What one map contributes to alignments: its truncated wall distance field and its wall cells
// (cell centres, cell units, grid frame). Built once per map, shared by all its alignments.
struct AlignmentTarget {
  // truncation_cells caps the distance field: the basin of convergence.
  explicit AlignmentTarget(const OccupancyGrid& grid, double truncation_cells = 6.0);
  // From the grid's OccupiedCellCenters: one pass over the grid for the field and the points.
  AlignmentTarget(const std::vector<Eigen::Vector2f>& wall_centres, double truncation_cells);
  // A target made before (a cache's): its field's parts (WallDistanceField) and the wall centres
  // it was made from.
  AlignmentTarget(const std::vector<Eigen::Vector2f>& wall_centres, double truncation_cells,
                  const Eigen::Array2i& offset_cells, const cv::Mat1f& distances,
                  const cv::Mat1b& flat);
  WallDistanceField field;
  std::vector<Eigen::Vector2d> wall_points;
};

struct LocalAlignmentResult {
  Pose2 T_ga_gb;           // refined, cell units
  double cost = 0.0;       // final robust cost per point
  bool converged = false;  // the solver ended at a finite pose and cost
};

LocalAlignmentResult RefineAlignment(const AlignmentTarget& a, const AlignmentTarget& b,
                                     const Pose2& T_ga_gb_initial,
                                     const LocalAlignmentOptions& options);

}  // namespace fleetmerge
