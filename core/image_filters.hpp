// The few image filters the pair search needs: a box maximum (binary dilation), the bounding box
// of non-zero pixels and a 5 x 5 Gaussian blur.
//
// Why not OpenCV's imgproc (cv::dilate, cv::boundingRect, cv::GaussianBlur): loading
// libopencv_imgproc costs every process about 3.5 ms before main on the CI machine (its
// initialisers fill ~500 KB of interpolation tables; docs/speed.md, "Where the time goes now"),
// and these are all the pair search used of it. On the search's small coarse images they also
// skip imgproc's per-call set-up (docs/speed.md, "How the work is shared").
// tests/core/image_filters_test checks each filter against imgproc.
#pragma once

#include <opencv2/core.hpp>

namespace fleetmerge {

// out(y, x) = max of image(y + dy, x + dx) over dy, dx in [-kBefore, kAfter] that fall inside
// the image: cv::dilate with a (kBefore + kAfter + 1)-square kernel anchored at
// (kBefore, kBefore) and a border that adds nothing (its default, or BORDER_REPLICATE: a
// replicated pixel is one the window already holds). Instantiated for <1, 1> (Mat1b, Mat1f)
// and <1, 2> (Mat1b).
template <int kBefore, int kAfter, typename T>
cv::Mat_<T> MaxFilter(const cv::Mat_<T>& image);

// The smallest rectangle holding every non-zero pixel (cv::boundingRect of a mask); empty when
// there is none. Scans each row from both ends, so a map's known interior is not visited.
cv::Rect NonZeroBox(const cv::Mat1b& mask);

// cv::GaussianBlur(image, out, cv::Size(5, 5), sigma): separable, the border reflected without
// repeating the edge pixel (BORDER_REFLECT_101). Agrees with OpenCV to float rounding (~1e-7).
cv::Mat1f GaussianBlur5x5(const cv::Mat1f& image, double sigma);

}  // namespace fleetmerge
