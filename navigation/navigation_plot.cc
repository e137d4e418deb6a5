#include "navigation/navigation_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "navigation/navigation_error.h"

namespace vio {
namespace {

const cv::Scalar kWhite(255, 255, 255);
const cv::Scalar kBlack(0, 0, 0);
const cv::Scalar kGridLine(225, 225, 225);
const cv::Scalar kPalette[] = {{150, 150, 150},  // grey
                               {200, 110, 0},    // blue
                               {40, 40, 210},    // red
                               {60, 160, 60},    // green
                               {0, 140, 255}};   // orange
const cv::Scalar kOccupied(70, 70, 70);
const cv::Scalar kInflated(200, 200, 200);
constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;
constexpr double kFontScale = 0.5;

cv::Scalar Colour(int index) { return kPalette[std::clamp(index, 0, 4)]; }

// A rectangle of the image showing the data window [x0, x1] x [y0, y1].
struct Panel {
  cv::Rect area;
  double x0, x1, y0, y1;
  cv::Point ToPixel(const Eigen::Vector2d& p) const {
    return {
        static_cast<int>(
            std::lround(area.x + (p.x() - x0) / (x1 - x0) * area.width)),
        static_cast<int>(std::lround(area.y + area.height -
                                     (p.y() - y0) / (y1 - y0) * area.height))};
  }
};

void PutText(cv::Mat& image, const std::string& text, cv::Point origin,
             double scale = kFontScale) {
  cv::putText(image, text, origin, kFont, scale, kBlack, 1, cv::LINE_AA);
}

int TextWidth(const std::string& text) {
  int baseline = 0;
  return cv::getTextSize(text, kFont, kFontScale, 1, &baseline).width;
}

// 1, 2 or 5 times a power of ten, about range / 6.
double NiceStep(double range) {
  const double raw = range / 6.0;
  const double decade = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0}) {
    if (m * decade >= raw) return m * decade;
  }
  return 10.0 * decade;
}

std::string Tick(double value, double step) {
  const int decimals =
      std::max(0, -static_cast<int>(std::floor(std::log10(step))));
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.*f", decimals,
                std::abs(value) < 1e-9 * step ? 0.0 : value);
  return buf;
}

void DrawAxes(cv::Mat& image, const Panel& p, const std::string& x_name,
              const std::string& y_name, bool grid_lines) {
  const double sx = NiceStep(p.x1 - p.x0), sy = NiceStep(p.y1 - p.y0);
  for (double x = std::ceil(p.x0 / sx) * sx; x <= p.x1; x += sx) {
    const cv::Point b = p.ToPixel({x, p.y0});
    if (grid_lines) cv::line(image, p.ToPixel({x, p.y1}), b, kGridLine, 1);
    cv::line(image, b, b + cv::Point(0, 5), kBlack, 1);
    const std::string label = Tick(x, sx);
    PutText(image, label, {b.x - TextWidth(label) / 2, b.y + 20});
  }
  for (double y = std::ceil(p.y0 / sy) * sy; y <= p.y1; y += sy) {
    const cv::Point l = p.ToPixel({p.x0, y});
    if (grid_lines) cv::line(image, l, p.ToPixel({p.x1, y}), kGridLine, 1);
    cv::line(image, l, l - cv::Point(5, 0), kBlack, 1);
    const std::string label = Tick(y, sy);
    PutText(image, label, {l.x - TextWidth(label) - 8, l.y + 5});
  }
  cv::rectangle(image, p.area, kBlack, 1);
  PutText(image, x_name,
          {p.area.x + (p.area.width - TextWidth(x_name)) / 2,
           p.area.y + p.area.height + 40});
  PutText(image, y_name, {p.area.x - 70, p.area.y - 8});
}

void DrawCurve(cv::Mat& image, const Panel& p, const PlotCurve& c) {
  std::vector<cv::Point> px;
  for (const Eigen::Vector2d& q : c.points) px.push_back(p.ToPixel(q));
  if (c.thickness == 0) {
    for (const cv::Point& q : px) {
      cv::circle(image, q, 1, Colour(c.colour), cv::FILLED, cv::LINE_AA);
    }
  } else if (px.size() >= 2) {
    cv::polylines(image, px, false, Colour(c.colour), c.thickness, cv::LINE_AA);
  }
}

// Legend box in the panel's upper-left corner: a swatch and a label per
// entry.
void DrawLegend(cv::Mat& image, const cv::Rect& area,
                const std::vector<PlotCurve>& entries) {
  int width = 0;
  for (const PlotCurve& c : entries)
    width = std::max(width, TextWidth(c.label));
  const cv::Rect box(area.x + 10, area.y + 10, width + 60,
                     12 + 20 * static_cast<int>(entries.size()));
  cv::rectangle(image, box, kWhite, cv::FILLED);
  cv::rectangle(image, box, kBlack, 1);
  for (size_t k = 0; k < entries.size(); ++k) {
    const int y = box.y + 16 + 20 * static_cast<int>(k);
    const cv::Scalar colour = Colour(entries[k].colour);
    if (entries[k].thickness == 0) {
      cv::circle(image, {box.x + 23, y}, 3, colour, cv::FILLED, cv::LINE_AA);
    } else {
      cv::line(image, {box.x + 8, y}, {box.x + 38, y}, colour,
               std::max(2, entries[k].thickness), cv::LINE_AA);
    }
    PutText(image, entries[k].label, {box.x + 46, y + 5});
  }
}

void Write(const std::string& path, const cv::Mat& image) {
  bool written = false;
  try {
    written = cv::imwrite(path, image);
  } catch (const cv::Exception& e) {
    throw NavigationError(path + ": cannot write the picture (" + e.what() +
                          ")");
  }
  if (!written) throw NavigationError(path + ": cannot write the picture");
}

// The bounding box of every point of the curves.
void Bounds(const std::vector<PlotCurve>& curves, Eigen::Vector2d* lo,
            Eigen::Vector2d* hi) {
  *lo = Eigen::Vector2d::Constant(1e300);
  *hi = Eigen::Vector2d::Constant(-1e300);
  for (const PlotCurve& c : curves) {
    for (const Eigen::Vector2d& p : c.points) {
      *lo = lo->cwiseMin(p);
      *hi = hi->cwiseMax(p);
    }
  }
}

}  // namespace

void WriteFilterPlot(const std::string& path, const std::string& title,
                     const std::vector<PlotCurve>& top,
                     const std::string& y_label,
                     const std::vector<PlotCurve>& bottom) {
  Eigen::Vector2d lo, hi;
  Bounds(top, &lo, &hi);
  if (lo.x() > hi.x()) {
    throw std::invalid_argument("WriteFilterPlot: no point to draw");
  }
  const int w = 1000, h = 1100, left = 100, right = 30;
  cv::Mat image(h, w, CV_8UC3, kWhite);
  PutText(image, title, {20, 28}, 0.6);
  // Top view: one scale on both axes, the data plus 10 %, at least 1 m.
  const cv::Rect top_area(left, 70, w - left - right, 600);
  const double m_per_px = 1.1 * std::max({(hi.x() - lo.x()) / top_area.width,
                                          (hi.y() - lo.y()) / top_area.height,
                                          1.0 / top_area.height});
  const Eigen::Vector2d c = 0.5 * (lo + hi);
  const double hx = 0.5 * m_per_px * top_area.width;
  const double hy = 0.5 * m_per_px * top_area.height;
  const Panel top_panel{top_area, c.x() - hx, c.x() + hx, c.y() - hy,
                        c.y() + hy};
  DrawAxes(image, top_panel, "x [m]", "y [m]", true);
  for (const PlotCurve& curve : top) DrawCurve(image, top_panel, curve);
  DrawLegend(image, top_area, top);

  Bounds(bottom, &lo, &hi);
  if (lo.x() < hi.x()) {
    const cv::Rect area(left, 790, w - left - right, 250);
    const double y_top =
        hi.y() > lo.y() ? hi.y() + 0.05 * (hi.y() - lo.y()) : lo.y() + 1e-3;
    const Panel panel{area, lo.x(), hi.x(), std::min(0.0, lo.y()), y_top};
    DrawAxes(image, panel, "time [s]", y_label, true);
    for (const PlotCurve& curve : bottom) DrawCurve(image, panel, curve);
    DrawLegend(image, area, bottom);
  }
  Write(path, image);
}

void WritePlanPlot(const std::string& path, const std::string& title,
                   const OccupancyGrid& g,
                   const std::vector<Eigen::Vector2d>& landmarks_xy,
                   const std::vector<Eigen::Vector2d>& trajectory_xy,
                   const std::vector<Eigen::Vector2d>& path_xy,
                   const Eigen::Vector2d& start_xy,
                   const Eigen::Vector2d& goal_xy) {
  const int gw = g.grid.width(), gh = g.grid.height();
  // Whole pixels per cell, the map about 900 px on its longer side.
  const int scale = std::max(1, 900 / std::max(gw, gh));
  const int left = 90, top = 60;
  const cv::Rect area(left, top, gw * scale, gh * scale);
  const int legend_w = 290;
  cv::Mat image(top + area.height + 70,
                std::max(left + area.width + 30 + legend_w, 600), CV_8UC3,
                kWhite);
  PutText(image, title, {20, 28}, 0.6);
  for (int y = 0; y < gh; ++y) {
    for (int x = 0; x < gw; ++x) {
      const Cell cell{x, y};
      if (!g.grid.Blocked(cell) && !g.Occupied(cell)) continue;
      const cv::Rect r(left + x * scale, top + y * scale, scale, scale);
      cv::rectangle(image, r, g.Occupied(cell) ? kOccupied : kInflated,
                    cv::FILLED);
    }
  }
  const Panel p{area, g.x_min_m, g.x_min_m + gw * g.cell_m,
                g.y_max_m - gh * g.cell_m, g.y_max_m};
  DrawAxes(image, p, "x [m]", "y [m]", false);
  const std::vector<PlotCurve> curves = {
      {"landmarks in the height band", landmarks_xy, 4, 0},
      {"trajectory (VIO)", trajectory_xy, 1, 1},
      {"planned path", path_xy, 2, 3}};
  for (const PlotCurve& c : curves) DrawCurve(image, p, c);
  cv::circle(image, p.ToPixel(start_xy), 7, Colour(3), 2, cv::LINE_AA);
  const cv::Point goal = p.ToPixel(goal_xy);
  cv::rectangle(image, goal - cv::Point(6, 6), goal + cv::Point(6, 6),
                Colour(2), 2, cv::LINE_AA);
  // Legend to the right of the map.
  const cv::Rect legend_area(left + area.width + 10, top - 10, legend_w, 10);
  DrawLegend(image, legend_area, curves);
  const int y0 = top + 16 + 20 * 3 + 12;
  const int x0 = legend_area.x + 18;
  cv::rectangle(image, {x0, y0 - 6}, {x0 + 12, y0 + 6}, kOccupied, cv::FILLED);
  PutText(image, "occupied cell", {x0 + 38, y0 + 5});
  cv::rectangle(image, {x0, y0 + 14}, {x0 + 12, y0 + 26}, kInflated,
                cv::FILLED);
  PutText(image, "within the radius", {x0 + 38, y0 + 25});
  cv::circle(image, {x0 + 6, y0 + 40}, 6, Colour(3), 2, cv::LINE_AA);
  PutText(image, "start", {x0 + 38, y0 + 45});
  cv::rectangle(image, {x0, y0 + 54}, {x0 + 12, y0 + 66}, Colour(2), 2);
  PutText(image, "goal", {x0 + 38, y0 + 65});
  Write(path, image);
}

}  // namespace vio
