// Where simulated robots may go and where they go next: cells with clearance, start cells,
// territories (the little-overlap mode) and frontier-like exploration goals with the shortest
// collision-free path to them. All cells are cells of the building's grid.
//
// Clearance comes from OpenCV's distanceTransform (exact Euclidean distance to the nearest cell
// that is not free); paths are breadth-first searches over the 8-connected traversable cells.
#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

#include "core/occupancy_grid.hpp"
#include "sim/portable_rng.hpp"

namespace fleetmerge {

// 255 where a robot of radius clearance_m may stand: free cells whose centre lies more than
// clearance_m from every cell that is not free (walls, unknown, outside the grid), restricted to
// the largest 8-connected region of them, so that every robot can reach every other.
cv::Mat1b TraversableCells(const OccupancyGrid& building, double clearance_m);

// `count` distinct start cells among the traversable ones: uniformly random, or with
// `spread_out` by farthest-point sampling (the first at random, each next one the traversable
// cell farthest in a straight line from the starts so far, so that the territories below are
// compact rather than rooms behind one wall). Throws fleetmerge::Error if there are fewer
// traversable cells than robots.
std::vector<Eigen::Array2i> ChooseStarts(const cv::Mat1b& traversable, int count, bool spread_out,
                                         PortableRng& rng);

// For each traversable cell the index of the start nearest to it along paths (a multi-source
// breadth-first search), -1 elsewhere. Each region is connected and contains its start.
cv::Mat1i Territories(const cv::Mat1b& traversable, const std::vector<Eigen::Array2i>& starts);

// The path to the next exploration goal: a breadth-first search from `from` over `walkable`
// finds the nearest walkable cell not yet `seen` (a frontier of what the robot knows), and the
// goal is drawn uniformly among the unseen walkable cells at most spread_cells steps further.
// Returns the cells from `from` (excluded) to the goal (included); empty when every walkable
// cell reachable from `from` has been seen.
std::vector<Eigen::Array2i> PathToNextGoal(const cv::Mat1b& walkable, const cv::Mat1b& seen,
                                           const Eigen::Array2i& from, int spread_cells,
                                           PortableRng& rng);

}  // namespace fleetmerge
