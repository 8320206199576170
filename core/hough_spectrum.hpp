// Discretised Hough transform (DHT) of a point set and its Hough spectrum (Section III-A).
//
// A line is rho = x cos(theta) + y sin(theta)            (Eq. 2)
// with theta in [0, pi) split into n_theta columns and rho into n_rho rows of rho_step_cells.
// Each point votes once per column, in the row its sinusoid crosses. The Hough spectrum is
//   HS(k) = sum_i H(i, k)^2,  k = 0 .. n_theta-1          (Section III-A, after Eq. 2)
// Rotating the points by psi shifts HS circularly by psi (period pi); translating them only
// shifts each column along rho, which leaves HS unchanged: that is why HS isolates rotation.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace fleetmerge {

struct HoughOptions {
  int n_theta = 180;            // columns over [0, pi): 1 degree each
  double rho_step_cells = 1.0;  // row height; n_rho follows from the points' extent
};

// The accumulator H, stored column-major (column k = theta_k is contiguous) because each column
// is filled and summed on its own.
struct HoughTransform {
  int n_theta = 0;
  int n_rho = 0;
  double rho_min = 0.0;  // rho of row 0's lower edge, relative to `center`
  double rho_step = 1.0;
  Eigen::Vector2f center = Eigen::Vector2f::Zero();  // rho is measured from here
  std::vector<int> votes;                            // votes[k * n_rho + i] = H(i, k)

  int at(int rho_index, int theta_index) const { return votes[theta_index * n_rho + rho_index]; }
  double theta_rad(int theta_index) const;
};

// DHT of `points` (cell units). rho is measured from the points' centroid so that n_rho stays
// as small as the point set allows. Throws fleetmerge::Error for n_theta < 2 or rho_step <= 0.
HoughTransform ComputeHoughTransform(const std::vector<Eigen::Vector2f>& points,
                                     const HoughOptions& options);

// HS(k) = sum_i H(i, k)^2.
std::vector<double> HoughSpectrum(const HoughTransform& transform);

}  // namespace fleetmerge
