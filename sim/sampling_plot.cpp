#include "sim/sampling_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <opencv2/imgproc.hpp>

namespace fleetmerge {
namespace {

const cv::Scalar kBlack(0, 0, 0), kGrey(200, 200, 200), kRandom(200, 90, 20), kEvery(30, 30, 210);
constexpr double kMinKept = 0.05;
constexpr int kWidth = 960, kPanelHeight = 260, kLeft = 80, kRight = 20, kTop = 30, kBottom = 40;

std::string Format(double v, const char* format) {
  char text[32];
  std::snprintf(text, sizeof text, format, v);
  return text;
}

// One panel at rows [y0, y0 + kPanelHeight): axes from x in [0, 1] and y in [lo, hi], a series
// per sampling mode; `value(s)` gives the plotted value and `range(s)` optional error bars.
void DrawPanel(cv::Mat& image, int y0, const std::vector<SamplingSummary>& summary,
               const std::string& label, double lo, double hi, const char* tick_format,
               const std::function<double(const SamplingSummary&)>& value,
               const std::function<std::pair<double, double>(const SamplingSummary&)>& range) {
  const int x_min = kLeft, x_max = kWidth - kRight;
  const int y_min = y0 + kTop, y_max = y0 + kPanelHeight - kBottom;  // image rows: top, bottom
  // x: log scale from 5 % to 100 % of the points, so that 1/k for k = 1..20 spreads out.
  auto px = [&](double x) {
    const double t = std::log(std::max(x, kMinKept) / kMinKept) / std::log(1.0 / kMinKept);
    return int(x_min + t * (x_max - x_min));
  };
  auto py = [&](double y) {
    const double t = std::clamp((y - lo) / (hi - lo), 0.0, 1.0);
    return int(y_max - t * (y_max - y_min));
  };
  for (int i = 0; i <= 4; ++i) {  // horizontal grid lines with their values
    const double y = lo + (hi - lo) * i / 4;
    cv::line(image, {x_min, py(y)}, {x_max, py(y)}, kGrey, 1);
    cv::putText(image, Format(y, tick_format), {5, py(y) + 5}, cv::FONT_HERSHEY_SIMPLEX, 0.45,
                kBlack, 1, cv::LINE_AA);
  }
  for (const int percent : {5, 10, 20, 30, 50, 70, 100}) {  // x ticks
    const int x = px(percent / 100.0);
    cv::line(image, {x, y_max}, {x, y_max + 5}, kBlack, 1);
    cv::putText(image, std::to_string(percent) + "%", {x - 14, y_max + 20},
                cv::FONT_HERSHEY_SIMPLEX, 0.4, kBlack, 1, cv::LINE_AA);
  }
  cv::rectangle(image, {x_min, y_min}, {x_max, y_max}, kBlack, 1);
  cv::putText(image, label, {x_min + 5, y0 + 20}, cv::FONT_HERSHEY_SIMPLEX, 0.55, kBlack, 1,
              cv::LINE_AA);
  for (const SamplingMode mode : {SamplingMode::kRandomFraction, SamplingMode::kEveryKth}) {
    const cv::Scalar colour = mode == SamplingMode::kEveryKth ? kEvery : kRandom;
    std::vector<std::pair<double, const SamplingSummary*>> points;
    for (const SamplingSummary& s : summary) {
      if (s.setting.mode == mode) points.emplace_back(s.setting.KeptFraction(), &s);
    }
    std::sort(points.begin(), points.end(),
              [](const auto& p, const auto& q) { return p.first < q.first; });
    for (std::size_t i = 0; i < points.size(); ++i) {
      const cv::Point p(px(points[i].first), py(value(*points[i].second)));
      if (range) {
        const auto [r_lo, r_hi] = range(*points[i].second);
        cv::line(image, {p.x, py(r_lo)}, {p.x, py(r_hi)}, colour, 1);
      }
      cv::circle(image, p, 3, colour, cv::FILLED, cv::LINE_AA);
      if (i > 0) {
        cv::line(image, {px(points[i - 1].first), py(value(*points[i - 1].second))}, p, colour, 1,
                 cv::LINE_AA);
      }
    }
  }
}

}  // namespace

cv::Mat DrawSamplingPlot(const std::vector<SamplingSummary>& summary, const std::string& title) {
  cv::Mat image(40 + 3 * kPanelHeight + 30, kWidth, CV_8UC3, cv::Scalar(255, 255, 255));
  cv::putText(image, title, {kLeft, 25}, cv::FONT_HERSHEY_SIMPLEX, 0.6, kBlack, 1, cv::LINE_AA);
  double max_time = 0.0, min_omega = 1.0;
  for (const SamplingSummary& s : summary) {
    max_time = std::max(max_time, s.median_time_ms);
    min_omega = std::min(min_omega, s.min_omega);
  }
  DrawPanel(image, 40, summary, "median time per pair [ms]", 0.0, std::max(1.0, max_time * 1.1),
            "%.1f", [](const SamplingSummary& s) { return s.median_time_ms; }, {});
  DrawPanel(
      image, 40 + kPanelHeight, summary, "best omega: mean, bars min..max",
      std::floor(min_omega * 20) / 20, 1.0, "%.3f",
      [](const SamplingSummary& s) { return s.mean_omega; },
      [](const SamplingSummary& s) { return std::make_pair(s.min_omega, s.max_omega); });
  DrawPanel(image, 40 + 2 * kPanelHeight, summary,
            "best hypothesis right (1 deg, 3 cells) [% of trials]", 0.0, 100.0, "%.0f",
            [](const SamplingSummary& s) { return 100.0 * s.success_rate; }, {});
  const int y = image.rows - 12;
  cv::putText(image, "x: share of occupied points used (Hough + X/Y spectra), log scale",
              {kLeft, y}, cv::FONT_HERSHEY_SIMPLEX, 0.45, kBlack, 1, cv::LINE_AA);
  cv::circle(image, {kWidth - 330, y - 4}, 4, kRandom, cv::FILLED);
  cv::putText(image, "random fraction", {kWidth - 320, y}, cv::FONT_HERSHEY_SIMPLEX, 0.45, kRandom,
              1, cv::LINE_AA);
  cv::circle(image, {kWidth - 170, y - 4}, 4, kEvery, cv::FILLED);
  cv::putText(image, "every k-th (1/k)", {kWidth - 160, y}, cv::FONT_HERSHEY_SIMPLEX, 0.45, kEvery,
              1, cv::LINE_AA);
  return image;
}

}  // namespace fleetmerge
