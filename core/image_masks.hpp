// Comparison masks and their combinations through OpenCV core's functions (cv::compare,
// cv::bitwise_and, cv::bitwise_or) instead of its matrix-expression operators (`image == v`,
// `a & b`, `k * image`, cv::Mat::zeros). The results are the same: the operators call these
// functions when the expression is assigned.
//
// Why: the `fleetmerge` executable links OpenCV core's static archive and so takes only the
// objects the pair path calls (cli/CMakeLists.txt). The matrix expressions live in an object
// whose static initialisers also reach OpenCV's LAPACK and BLAS solvers: one expression on the
// pair path would make every start load LAPACK, BLAS and the Fortran runtime (~1.5 ms on the CI
// machine, docs/speed.md, "Where the time goes now"). The executable does not link them, so
// such an expression fails its link instead of slowing it silently.
#pragma once

#include <opencv2/core.hpp>

namespace fleetmerge {

// 255 where `image op value` holds, else 0 (op: cv::CMP_EQ, cv::CMP_NE, cv::CMP_GT, ...).
inline cv::Mat1b CompareMask(const cv::Mat& image, cv::CmpTypes op, double value) {
  cv::Mat1b mask;
  cv::compare(image, value, mask, op);
  return mask;
}

inline cv::Mat1b MaskAnd(const cv::Mat1b& a, const cv::Mat1b& b) {
  cv::Mat1b out;
  cv::bitwise_and(a, b, out);
  return out;
}

inline cv::Mat1b MaskOr(const cv::Mat1b& a, const cv::Mat1b& b) {
  cv::Mat1b out;
  cv::bitwise_or(a, b, out);
  return out;
}

}  // namespace fleetmerge
