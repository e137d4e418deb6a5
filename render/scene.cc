#include "render/scene.h"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace vio {
namespace {

bool Fail(std::string* message, const std::string& text) {
  *message = text;
  return false;
}

bool Positive(double v) { return std::isfinite(v) && v > 0.0; }

ScenePlane Plane(const Eigen::Vector3d& origin, const Eigen::Vector3d& u,
                 const Eigen::Vector3d& v, double size_u, double size_v) {
  ScenePlane p;
  p.origin_w = origin;
  p.axis_u_w = u;
  p.axis_v_w = v;
  p.size_u_m = size_u;
  p.size_v_m = size_v;
  return p;
}

}  // namespace

bool ScenePlane::IsValid() const {
  constexpr double kTolerance = 1e-9;
  return origin_w.allFinite() && axis_u_w.allFinite() && axis_v_w.allFinite() &&
         Positive(size_u_m) && Positive(size_v_m) &&
         std::abs(axis_u_w.norm() - 1.0) < kTolerance &&
         std::abs(axis_v_w.norm() - 1.0) < kTolerance &&
         std::abs(axis_u_w.dot(axis_v_w)) < kTolerance;
}

Eigen::Vector3d SceneLayout::FloorCentre() const {
  return Eigen::Vector3d(0.5 * (min_corner.x() + max_corner.x()),
                         0.5 * (min_corner.y() + max_corner.y()),
                         min_corner.z());
}

bool SceneLayout::Validate(std::string* message) const {
  const Eigen::Vector3d size = max_corner - min_corner;
  if (!min_corner.allFinite() || !max_corner.allFinite() ||
      !Positive(size.x()) || !Positive(size.y()) || !Positive(size.z())) {
    return Fail(message, "room sizes must be > 0");
  }
  const double half_length_x_m = 0.5 * size.x();
  const double half_width_y_m = 0.5 * size.y();
  const double height_m = size.z();
  for (size_t i = 0; i < boxes.size(); ++i) {
    const SceneBox& b = boxes[i];
    const std::string name = "boxes[" + std::to_string(i) + "]";
    if (!b.center_xy_m.allFinite()) {
      return Fail(message, name + ".center_xy_m must be finite");
    }
    if (!Positive(b.size_m.x()) || !Positive(b.size_m.y()) ||
        !Positive(b.size_m.z())) {
      return Fail(message, name + ".size_m must be > 0");
    }
    if (std::abs(b.center_xy_m.x()) + 0.5 * b.size_m.x() >= half_length_x_m ||
        std::abs(b.center_xy_m.y()) + 0.5 * b.size_m.y() >= half_width_y_m ||
        b.size_m.z() >= height_m) {
      return Fail(message, name + " must lie inside the room");
    }
    for (size_t j = 0; j < i; ++j) {
      const SceneBox& o = boxes[j];
      const Eigen::Vector2d gap = (b.center_xy_m - o.center_xy_m).cwiseAbs() -
                                  0.5 * (b.size_m + o.size_m).head<2>();
      if (gap.x() < 0.0 && gap.y() < 0.0) {
        return Fail(message,
                    name + " overlaps boxes[" + std::to_string(j) + "]");
      }
    }
  }
  return true;
}

SceneGeometry::SceneGeometry(std::vector<ScenePlane> planes, int num_enclosing)
    : planes_(std::move(planes)), num_enclosing_(num_enclosing) {
  if (num_enclosing < 0 || num_enclosing > static_cast<int>(planes_.size())) {
    throw std::invalid_argument("scene: num_enclosing out of range");
  }
  for (size_t i = 0; i < planes_.size(); ++i) {
    if (!planes_[i].IsValid()) {
      throw std::invalid_argument("scene plane " + std::to_string(i) +
                                  " is invalid (axes not orthonormal, a size "
                                  "not > 0 or a value not finite)");
    }
  }
}

bool SceneGeometry::Intersect(const Eigen::Vector3d& origin_w,
                              const Eigen::Vector3d& direction_w, SceneHit* hit,
                              double min_t) const {
  // Ray o + t d meets the plane n.(X - origin) = 0 at
  // t = n.(origin - o) / n.d, from the visible side when n.d < 0.
  constexpr double kEdge = 1e-9;  // [m] rectangle bounds are inclusive
  double best_t = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < planes_.size(); ++i) {
    const ScenePlane& p = planes_[i];
    const Eigen::Vector3d n = p.Normal();
    const double n_d = n.dot(direction_w);
    if (!(n_d < 0.0)) continue;
    const double t = n.dot(p.origin_w - origin_w) / n_d;
    if (!(t > min_t) || t >= best_t) continue;
    const Eigen::Vector3d r = origin_w + t * direction_w - p.origin_w;
    const double a = r.dot(p.axis_u_w);
    const double b = r.dot(p.axis_v_w);
    if (a < -kEdge || a > p.size_u_m + kEdge || b < -kEdge ||
        b > p.size_v_m + kEdge) {
      continue;
    }
    best_t = t;
    hit->plane = static_cast<int>(i);
    hit->ab = Eigen::Vector2d(a, b);
  }
  if (!std::isfinite(best_t)) return false;
  hit->distance = best_t * direction_w.norm();
  return true;
}

bool SceneGeometry::Visible(const Eigen::Vector3d& eye_w,
                            const Eigen::Vector3d& point_w,
                            double tolerance_m) const {
  const Eigen::Vector3d d = point_w - eye_w;
  SceneHit hit;
  if (!Intersect(eye_w, d, &hit)) return true;
  return hit.distance >= d.norm() - tolerance_m;
}

SceneGeometry MakeRoomScene(const SceneLayout& layout) {
  std::string message;
  if (!layout.Validate(&message)) {
    throw std::invalid_argument("scene layout: " + message);
  }
  const Eigen::Vector3d x = Eigen::Vector3d::UnitX();
  const Eigen::Vector3d y = Eigen::Vector3d::UnitY();
  const Eigen::Vector3d z = Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d size = layout.max_corner - layout.min_corner;
  const double hx = 0.5 * size.x(), hy = 0.5 * size.y(), h = size.z();
  // Built around the floor centre c, then shifted there.
  const Eigen::Vector3d c = layout.FloorCentre();
  // Room: normals inwards; walls with u horizontal and v up.
  std::vector<ScenePlane> planes = {
      Plane(c + Eigen::Vector3d(-hx, -hy, 0), x, y, 2 * hx, 2 * hy),  // floor
      Plane(c + Eigen::Vector3d(-hx, -hy, h), y, x, 2 * hy, 2 * hx),  // ceiling
      Plane(c + Eigen::Vector3d(-hx, -hy, 0), y, z, 2 * hy, h),       // n = +x
      Plane(c + Eigen::Vector3d(hx, hy, 0), -y, z, 2 * hy, h),        // n = -x
      Plane(c + Eigen::Vector3d(hx, -hy, 0), -x, z, 2 * hx, h),       // n = +y
      Plane(c + Eigen::Vector3d(-hx, hy, 0), x, z, 2 * hx, h),        // n = -y
  };
  const int room_planes = static_cast<int>(planes.size());
  // Boxes: normals outwards, no bottom.
  for (const SceneBox& b : layout.boxes) {
    const double x0 = c.x() + b.center_xy_m.x() - 0.5 * b.size_m.x();
    const double x1 = c.x() + b.center_xy_m.x() + 0.5 * b.size_m.x();
    const double y0 = c.y() + b.center_xy_m.y() - 0.5 * b.size_m.y();
    const double y1 = c.y() + b.center_xy_m.y() + 0.5 * b.size_m.y();
    const double z0 = c.z(), z1 = c.z() + b.size_m.z();
    const double sx = b.size_m.x(), sy = b.size_m.y(), sz = b.size_m.z();
    planes.push_back(Plane({x0, y0, z1}, x, y, sx, sy));   // top, n = +z
    planes.push_back(Plane({x1, y0, z0}, y, z, sy, sz));   // n = +x
    planes.push_back(Plane({x0, y1, z0}, -y, z, sy, sz));  // n = -x
    planes.push_back(Plane({x1, y1, z0}, -x, z, sx, sz));  // n = +y
    planes.push_back(Plane({x0, y0, z0}, x, z, sx, sz));   // n = -y
  }
  return SceneGeometry(std::move(planes), room_planes);
}

}  // namespace vio
