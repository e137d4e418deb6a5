#include "tools/curve_fitting/curve_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <vector>

namespace vio {

namespace {

constexpr int kWidth = 1000, kHeight = 650;                      // [px]
constexpr int kLeft = 80, kRight = 30, kTop = 50, kBottom = 60;  // [px]
constexpr int kCurvePoints = 400;

const cv::Scalar kBlack(0, 0, 0), kGrey(200, 200, 200);
const cv::Scalar kSampleColour(120, 120, 120), kOutlierColour(0, 0, 220);
const cv::Scalar kTruthColour(0, 0, 0), kCeresColour(230, 160, 60);
const cv::Scalar kLmColour(0, 150, 255);

// Maps data coordinates to pixels.
struct Axes {
  double x_min, x_max, y_min, y_max;
  cv::Point ToPixel(double x, double y) const {
    const double u =
        kLeft + (x - x_min) / (x_max - x_min) * (kWidth - kLeft - kRight);
    const double v = kHeight - kBottom -
                     (y - y_min) / (y_max - y_min) * (kHeight - kTop - kBottom);
    return cv::Point(static_cast<int>(std::lround(u)),
                     static_cast<int>(std::lround(v)));
  }
};

// A 1, 2 or 5 times a power of ten giving about `intervals` over range.
double NiceStep(double range, double intervals) {
  const double raw = range / intervals;
  const double decade = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0}) {
    if (m * decade >= raw) return m * decade;
  }
  return 10.0 * decade;
}

void PutText(cv::Mat* image, const std::string& text, cv::Point at,
             double scale = 0.5, const cv::Scalar& colour = kBlack) {
  cv::putText(*image, text, at, cv::FONT_HERSHEY_SIMPLEX, scale, colour, 1,
              cv::LINE_AA);
}

std::string Format(double value, const char* format) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), format, value);
  return buffer;
}

void DrawAxes(cv::Mat* image, const Axes& axes) {
  const double x_step = NiceStep(axes.x_max - axes.x_min, 5.0);
  const double y_step = NiceStep(axes.y_max - axes.y_min, 8.0);
  // Ticks at integer multiples of the step: no drift, no "-0" labels.
  for (long j = std::lround(std::ceil(axes.x_min / x_step));
       j * x_step <= axes.x_max + 1e-9 * x_step; ++j) {
    const cv::Point p = axes.ToPixel(j * x_step, axes.y_min);
    cv::line(*image, p, {p.x, kTop}, kGrey, 1);
    cv::line(*image, p, {p.x, p.y + 6}, kBlack, 1);
    PutText(image, Format(j * x_step, "%.1f"), {p.x - 12, p.y + 24});
  }
  for (long j = std::lround(std::ceil(axes.y_min / y_step));
       j * y_step <= axes.y_max; ++j) {
    const cv::Point p = axes.ToPixel(axes.x_min, j * y_step);
    cv::line(*image, p, {kWidth - kRight, p.y}, kGrey, 1);
    cv::line(*image, {p.x - 6, p.y}, p, kBlack, 1);
    PutText(image, Format(j * y_step, "%g"), {8, p.y + 5});
  }
  cv::rectangle(*image, cv::Point(kLeft, kTop),
                cv::Point(kWidth - kRight, kHeight - kBottom), kBlack, 1);
  PutText(image, "x", {kWidth / 2, kHeight - 15}, 0.6);
  PutText(image, "y", {10, kTop - 15}, 0.6);
}

// A polyline of y = exp(a x^2 + b x + c); dashed draws every other segment.
void DrawCurve(cv::Mat* image, const Axes& axes, const Eigen::Vector3d& p,
               const cv::Scalar& colour, int thickness, bool dashed) {
  std::vector<cv::Point> points;
  for (int i = 0; i <= kCurvePoints; ++i) {
    const double x = axes.x_min + (axes.x_max - axes.x_min) * i / kCurvePoints;
    const double y = std::clamp(CurveModel(p, x), axes.y_min, axes.y_max);
    points.push_back(axes.ToPixel(x, y));
  }
  for (size_t i = 1; i < points.size(); ++i) {
    if (dashed && (i / 6) % 2 == 1) continue;
    cv::line(*image, points[i - 1], points[i], colour, thickness, cv::LINE_AA);
  }
}

void DrawLegend(cv::Mat* image, bool with_outliers) {
  const cv::Point origin(kLeft + 15, kTop + 15);
  const cv::Point size(230, with_outliers ? 112 : 90);
  cv::rectangle(*image, origin, origin + size, cv::Scalar::all(255),
                cv::FILLED);
  cv::rectangle(*image, origin, origin + size, kBlack, 1);
  int y = origin.y + 20;
  const int x = origin.x + 12;
  cv::circle(*image, {x + 15, y - 4}, 3, kSampleColour, cv::FILLED,
             cv::LINE_AA);
  PutText(image, "samples", {x + 45, y});
  if (with_outliers) {
    y += 22;
    cv::drawMarker(*image, {x + 15, y - 4}, kOutlierColour,
                   cv::MARKER_TILTED_CROSS, 9, 2);
    PutText(image, "injected outliers", {x + 45, y});
  }
  y += 22;
  cv::line(*image, {x, y - 4}, {x + 30, y - 4}, kCeresColour, 5, cv::LINE_AA);
  PutText(image, "Ceres LM fit", {x + 45, y});
  y += 22;
  cv::line(*image, {x, y - 4}, {x + 12, y - 4}, kLmColour, 3, cv::LINE_AA);
  cv::line(*image, {x + 18, y - 4}, {x + 30, y - 4}, kLmColour, 3, cv::LINE_AA);
  PutText(image, "hand LM fit (dashed)", {x + 45, y});
  y += 22;
  cv::line(*image, {x, y - 4}, {x + 30, y - 4}, kTruthColour, 1, cv::LINE_AA);
  PutText(image, "ground truth", {x + 45, y});
}

}  // namespace

void WriteCurvePlot(const std::string& path, const CurvePlot& plot) {
  if (plot.samples == nullptr) {
    throw std::invalid_argument("WriteCurvePlot: no samples");
  }
  const CurveSamples& samples = *plot.samples;
  double y_min = 0.0, y_max = 1.0;
  for (double y : samples.y) {
    y_min = std::min(y_min, y);
    y_max = std::max(y_max, y);
  }
  const double pad = 0.05 * (y_max - y_min);
  const Axes axes{0.0, 1.0, y_min - pad, y_max + pad};

  cv::Mat image(kHeight, kWidth, CV_8UC3, cv::Scalar::all(255));
  DrawAxes(&image, axes);
  for (size_t i = 0; i < samples.x.size(); ++i) {
    const cv::Point p = axes.ToPixel(samples.x[i], samples.y[i]);
    if (samples.is_outlier[i]) {
      cv::drawMarker(image, p, kOutlierColour, cv::MARKER_TILTED_CROSS, 9, 2);
    } else {
      cv::circle(image, p, 3, kSampleColour, cv::FILLED, cv::LINE_AA);
    }
  }
  // Widest first, so that coinciding curves all stay visible.
  DrawCurve(&image, axes, plot.ceres_fit, kCeresColour, 5, false);
  DrawCurve(&image, axes, plot.lm_fit, kLmColour, 3, true);
  DrawCurve(&image, axes, plot.truth, kTruthColour, 1, false);
  const bool with_outliers =
      std::find(samples.is_outlier.begin(), samples.is_outlier.end(), true) !=
      samples.is_outlier.end();
  DrawLegend(&image, with_outliers);
  PutText(&image, plot.title, {kLeft, kTop - 18}, 0.6);

  bool written = false;
  try {
    written = cv::imwrite(path, image);
  } catch (const cv::Exception& e) {
    throw std::runtime_error(path + ": cannot write the plot (" + e.what() +
                             ")");
  }
  if (!written) throw std::runtime_error(path + ": cannot write the plot");
}

}  // namespace vio
