#include "render/polygon.h"

namespace vio {

Polygon ClipPolygon(const Polygon& polygon, const Eigen::Vector4d& k) {
  Polygon out;
  const size_t n = polygon.size();
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d& a = polygon[i];
    const Eigen::Vector3d& b = polygon[(i + 1) % n];
    const double fa = k.head<3>().dot(a) + k[3];
    const double fb = k.head<3>().dot(b) + k[3];
    if (fa >= 0.0) out.push_back(a);
    // The edge crosses the boundary: f is affine along it, so the crossing
    // is at the parameter fa / (fa - fb).
    if ((fa >= 0.0) != (fb >= 0.0)) {
      out.push_back(a + (fa / (fa - fb)) * (b - a));
    }
  }
  return out;
}

}  // namespace vio
