#include "eval/plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "eval/eval_error.h"

namespace vio {
namespace {

// Colours (BGR) and text style.
const cv::Scalar kWhite(255, 255, 255);
const cv::Scalar kBlack(0, 0, 0);
const cv::Scalar kGrid(225, 225, 225);
const cv::Scalar kGroundTruth(150, 150, 150);
const cv::Scalar kEstimate(200, 110, 0);
const cv::Scalar kError(40, 40, 210);
constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;
constexpr double kFontScale = 0.5;
constexpr double kTitleScale = 0.6;

// A rectangle of the image showing the data window [x0, x1] x [y0, y1].
struct Panel {
  cv::Rect area;
  double x0, x1, y0, y1;

  cv::Point ToPixel(double x, double y) const {
    const double u = area.x + (x - x0) / (x1 - x0) * area.width;
    const double v = area.y + area.height - (y - y0) / (y1 - y0) * area.height;
    return {static_cast<int>(std::lround(u)), static_cast<int>(std::lround(v))};
  }
};

// 1, 2 or 5 times a power of ten, about range / 6: readable tick spacing.
double NiceStep(double range) {
  const double raw = range / 6.0;
  const double decade = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0}) {
    if (m * decade >= raw) return m * decade;
  }
  return 10.0 * decade;
}

std::string TickLabel(double value, double step) {
  const int decimals =
      std::max(0, -static_cast<int>(std::floor(std::log10(step))));
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.*f", decimals,
                std::abs(value) < 1e-12 * step ? 0.0 : value);
  return buf;
}

void PutText(cv::Mat& image, const std::string& text, cv::Point origin,
             double scale = kFontScale, const cv::Scalar& colour = kBlack) {
  cv::putText(image, text, origin, kFont, scale, colour, 1, cv::LINE_AA);
}

cv::Size TextSize(const std::string& text, double scale = kFontScale) {
  int baseline = 0;
  return cv::getTextSize(text, kFont, scale, 1, &baseline);
}

// Text turned 90 degrees counter-clockwise, centred on `centre` (y labels).
void PutVerticalText(cv::Mat& image, const std::string& text,
                     cv::Point centre) {
  const cv::Size size = TextSize(text);
  cv::Mat strip(size.height + 8, size.width + 4, CV_8UC3, kWhite);
  PutText(strip, text, {2, size.height + 2});
  cv::Mat turned;
  cv::rotate(strip, turned, cv::ROTATE_90_COUNTERCLOCKWISE);
  const cv::Rect where(centre.x - turned.cols / 2, centre.y - turned.rows / 2,
                       turned.cols, turned.rows);
  if ((where & cv::Rect(0, 0, image.cols, image.rows)) == where) {
    turned.copyTo(image(where));
  }
}

// Grid lines, tick labels and the axis names of a panel.
void DrawAxes(cv::Mat& image, const Panel& panel, const std::string& x_name,
              const std::string& y_name) {
  const double step_x = NiceStep(panel.x1 - panel.x0);
  const double step_y = NiceStep(panel.y1 - panel.y0);
  for (double x = std::ceil(panel.x0 / step_x) * step_x; x <= panel.x1;
       x += step_x) {
    const cv::Point top = panel.ToPixel(x, panel.y1);
    const cv::Point bottom = panel.ToPixel(x, panel.y0);
    cv::line(image, top, bottom, kGrid, 1);
    const std::string label = TickLabel(x, step_x);
    PutText(image, label,
            {bottom.x - TextSize(label).width / 2, bottom.y + 18});
  }
  for (double y = std::ceil(panel.y0 / step_y) * step_y; y <= panel.y1;
       y += step_y) {
    const cv::Point left = panel.ToPixel(panel.x0, y);
    const cv::Point right = panel.ToPixel(panel.x1, y);
    cv::line(image, left, right, kGrid, 1);
    const std::string label = TickLabel(y, step_y);
    PutText(image, label, {left.x - TextSize(label).width - 6, left.y + 5});
  }
  cv::rectangle(image, panel.area, kBlack, 1);
  const cv::Size x_size = TextSize(x_name);
  PutText(image, x_name,
          {panel.area.x + (panel.area.width - x_size.width) / 2,
           panel.area.y + panel.area.height + 40});
  PutVerticalText(image, y_name,
                  {panel.area.x - 72, panel.area.y + panel.area.height / 2});
}

void DrawPolyline(cv::Mat& image, const std::vector<cv::Point>& points,
                  const cv::Scalar& colour, int thickness) {
  if (points.size() >= 2) {
    cv::polylines(image, points, false, colour, thickness, cv::LINE_AA);
  }
}

void DrawLegend(cv::Mat& image, const Panel& panel,
                const PlotOptions& options) {
  const std::string* labels[] = {&options.ground_truth_label,
                                 &options.estimate_label};
  const cv::Scalar colours[] = {kGroundTruth, kEstimate};
  int width = 0;
  for (const std::string* l : labels)
    width = std::max(width, TextSize(*l).width);
  const cv::Rect box(panel.area.x + 10, panel.area.y + 10, width + 60, 50);
  cv::rectangle(image, box, kWhite, cv::FILLED);
  cv::rectangle(image, box, kBlack, 1);
  for (int k = 0; k < 2; ++k) {
    const int y = box.y + 17 + 20 * k;
    cv::line(image, {box.x + 8, y}, {box.x + 38, y}, colours[k], 3 - k,
             cv::LINE_AA);
    PutText(image, *labels[k], {box.x + 46, y + 5});
  }
}

// Top view: equal metres per pixel on both axes, the data centred.
void DrawTopView(cv::Mat& image, const cv::Rect& area,
                 const Trajectory& ground_truth,
                 const Trajectory& aligned_estimate,
                 const PlotOptions& options) {
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  for (const Trajectory* t : {&ground_truth, &aligned_estimate}) {
    for (const StampedPose& p : *t) {
      x0 = std::min(x0, p.p_w_b.x());
      x1 = std::max(x1, p.p_w_b.x());
      y0 = std::min(y0, p.p_w_b.y());
      y1 = std::max(y1, p.p_w_b.y());
    }
  }
  // One scale for both axes: the data plus 10 %, at least 1 m across.
  const double metres_per_px =
      std::max({(x1 - x0) / area.width, (y1 - y0) / area.height,
                1.0 / std::min(area.width, area.height)}) *
      1.1;
  const double cx = 0.5 * (x0 + x1), cy = 0.5 * (y0 + y1);
  const double hx = 0.5 * metres_per_px * area.width;
  const double hy = 0.5 * metres_per_px * area.height;
  const Panel panel{area, cx - hx, cx + hx, cy - hy, cy + hy};
  DrawAxes(image, panel, "x [m]", "y [m]");

  std::vector<cv::Point> gt_px, est_px;
  for (const StampedPose& p : ground_truth) {
    gt_px.push_back(panel.ToPixel(p.p_w_b.x(), p.p_w_b.y()));
  }
  for (const StampedPose& p : aligned_estimate) {
    est_px.push_back(panel.ToPixel(p.p_w_b.x(), p.p_w_b.y()));
  }
  DrawPolyline(image, gt_px, kGroundTruth, 3);
  DrawPolyline(image, est_px, kEstimate, 1);
  cv::circle(image, gt_px.front(), 6, kGroundTruth, 2, cv::LINE_AA);
  PutText(image, "start", gt_px.front() + cv::Point(9, -6));
  DrawLegend(image, panel, options);
}

// Error over time since the first associated stamp, with its RMSE.
void DrawErrorOverTime(cv::Mat& image, const cv::Rect& area,
                       const Trajectory& aligned_estimate,
                       const std::vector<double>& error_m,
                       const std::string& time_label) {
  const int64_t t0_ns = aligned_estimate.front().t_ns;
  const double duration =
      std::max(1e-3, (aligned_estimate.back().t_ns - t0_ns) * 1e-9);
  double max_error = 0.0, sum_sq = 0.0;
  for (double e : error_m) {
    max_error = std::max(max_error, e);
    sum_sq += e * e;
  }
  const double rmse = std::sqrt(sum_sq / error_m.size());
  // At least 1 mm tall, so that a (near) perfect estimate gets short labels.
  const Panel panel{area, 0.0, duration, 0.0, std::max(1.1 * max_error, 1e-3)};
  DrawAxes(image, panel, time_label, "position error [m]");
  std::vector<cv::Point> points;
  for (size_t i = 0; i < error_m.size(); ++i) {
    const double t = (aligned_estimate[i].t_ns - t0_ns) * 1e-9;
    points.push_back(panel.ToPixel(t, error_m[i]));
  }
  DrawPolyline(image, points, kError, 1);
  // Dashed RMSE line, labelled at its right end.
  const cv::Point a = panel.ToPixel(0.0, rmse),
                  b = panel.ToPixel(duration, rmse);
  for (int x = a.x; x < b.x; x += 12) {
    cv::line(image, {x, a.y}, {std::min(x + 6, b.x), a.y}, kBlack, 1);
  }
  char label[64];
  std::snprintf(label, sizeof(label), "rmse %.4g m", rmse);
  const cv::Size size = TextSize(label);
  const cv::Point origin(b.x - size.width - 6, a.y - 6);
  cv::rectangle(image, origin + cv::Point(-3, 4),
                origin + cv::Point(size.width + 3, -size.height - 4), kWhite,
                cv::FILLED);
  PutText(image, label, origin);
}

}  // namespace

void WriteEvaluationPlot(const std::string& path,
                         const Trajectory& ground_truth,
                         const Trajectory& aligned_estimate,
                         const std::vector<double>& error_m,
                         const PlotOptions& options) {
  if (ground_truth.empty() || ground_truth.size() != aligned_estimate.size() ||
      error_m.size() != ground_truth.size()) {
    throw std::invalid_argument(
        "WriteEvaluationPlot: needs equally long, non-empty trajectories and "
        "errors");
  }
  if (options.width_px < 400 || options.height_px < 400) {
    throw std::invalid_argument(
        "WriteEvaluationPlot: image smaller than 400 px");
  }
  const int w = options.width_px, h = options.height_px;
  cv::Mat image(h, w, CV_8UC3, kWhite);
  // The title shrinks to fit the width (long file names).
  const double title_scale =
      options.title.empty()
          ? kTitleScale
          : std::min(kTitleScale,
                     kTitleScale * (w - 40) /
                         TextSize(options.title, kTitleScale).width);
  PutText(image, options.title, {20, 28}, title_scale);
  PutText(image, "top view (x-y plane of the ground-truth world)", {90, 52});
  const int left = 100, right = 30;
  const int top_height = (h - 60) * 2 / 3 - 80;
  DrawTopView(image, cv::Rect(left, 62, w - left - right, top_height),
              ground_truth, aligned_estimate, options);
  const int bottom_y = 62 + top_height + 80;  // below the x label
  PutText(image, "position error of each associated pose", {90, bottom_y - 10});
  DrawErrorOverTime(
      image, cv::Rect(left, bottom_y, w - left - right, h - bottom_y - 50),
      aligned_estimate, error_m, options.time_label);
  bool written = false;
  try {
    written = cv::imwrite(path, image);
  } catch (const cv::Exception& e) {
    throw EvalError(path + ": cannot write the plot (" + e.what() + ")");
  }
  if (!written) throw EvalError(path + ": cannot write the plot");
}

}  // namespace vio
