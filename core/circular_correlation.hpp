// Circular cross-correlation of two Hough spectra and its local maxima (Section III-A, Fig. 1).
//
// If map b is map a rotated by psi, HS_b(theta) = HS_a(theta - psi) over the period pi, so
//   C(k) = sum_i HS_a((i + k) mod n) * HS_b(i)
// peaks at k = psi / (pi / n). Each local maximum is a rotation hypothesis psi_i; because the
// spectrum has period pi, psi_i + pi is equally likely and is tried as well (by the caller).
#pragma once

#include <vector>

namespace fleetmerge {

// C(k) = sum_i a[(i + k) mod n] * b[i]. Throws fleetmerge::Error if the sizes differ.
std::vector<double> CircularCrossCorrelation(const std::vector<double>& a,
                                             const std::vector<double>& b);

struct Peak {
  double position = 0.0;  // in bins, refined below one bin by a parabola through 3 samples
  double value = 0.0;
};

// The `count` largest circular local maxima (s[k] > both neighbours, or a plateau's first
// sample), largest first.
std::vector<Peak> CircularLocalMaxima(const std::vector<double>& signal, int count);

}  // namespace fleetmerge
