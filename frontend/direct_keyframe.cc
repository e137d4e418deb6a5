#include "frontend/direct_keyframe.h"

#include <algorithm>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>

namespace vio {

std::vector<DepthPoint> CoarserDepthPoints(
    const std::vector<DepthPoint>& points, const PyramidLevel& coarser) {
  struct Sums {
    int n = 0;
    double w = 0.0, w_rho = 0.0, w_rho2 = 0.0;
  };
  const int width = coarser.image->width(), height = coarser.image->height();
  // Ordered by pixel index, so the output order is fixed (row-major).
  std::map<int, Sums> blocks;
  for (const DepthPoint& p : points) {
    const int u = static_cast<int>(p.uv.x()) / 2;
    const int v = static_cast<int>(p.uv.y()) / 2;
    if (u >= width || v >= height || !(p.variance > 0.0)) continue;
    Sums& s = blocks[v * width + u];
    const double w = 1.0 / p.variance;
    ++s.n;
    s.w += w;
    s.w_rho += w * p.rho;
    s.w_rho2 += w * p.rho * p.rho;
  }
  std::vector<DepthPoint> out;
  out.reserve(blocks.size());
  for (const auto& [index, s] : blocks) {
    DepthPoint p;
    const int u = index % width, v = index / width;
    p.uv = Eigen::Vector2d(u, v);
    p.intensity = coarser.image->At(u, v);
    p.rho = s.w_rho / s.w;
    const double spread = std::max(0.0, s.w_rho2 / s.w - p.rho * p.rho);
    p.variance = s.n / s.w + spread;
    out.push_back(p);
  }
  return out;
}

DirectKeyframe MakeDirectKeyframe(int64_t t_ns, const ImagePyramid& image,
                                  std::vector<DepthPoint> points, int level) {
  if (level < 0 || level >= image.size()) {
    throw std::invalid_argument(
        "MakeDirectKeyframe: level " + std::to_string(level) + " of a " +
        std::to_string(image.size()) + "-level pyramid");
  }
  DirectKeyframe kf;
  kf.t_ns = t_ns;
  kf.image = image;
  kf.points.resize(image.size());
  if (!points.empty()) {
    std::vector<double> depths;
    for (const DepthPoint& p : points) depths.push_back(1.0 / p.rho);
    std::nth_element(depths.begin(), depths.begin() + depths.size() / 2,
                     depths.end());
    kf.median_depth_m = depths[depths.size() / 2];
  }
  kf.points[level] = std::move(points);
  for (int l = level + 1; l < image.size(); ++l) {
    kf.points[l] = CoarserDepthPoints(kf.points[l - 1], image.level(l));
  }
  return kf;
}

}  // namespace vio
