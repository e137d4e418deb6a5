#include "dataset/flight_room.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace vio {
namespace {

// Uniform points on the six faces of the box, each face's share
// proportional to its area.
void AddSurface(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, int n,
                std::mt19937* rng, std::vector<Eigen::Vector3d>* out) {
  const Eigen::Vector3d size = hi - lo;
  // Faces: floor, ceiling (z), walls x = lo, hi, walls y = lo, hi.
  const double areas[6] = {size.x() * size.y(), size.x() * size.y(),
                           size.y() * size.z(), size.y() * size.z(),
                           size.x() * size.z(), size.x() * size.z()};
  std::discrete_distribution<int> face(std::begin(areas), std::end(areas));
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int i = 0; i < n; ++i) {
    const int f = face(*rng);
    const double a = unit(*rng), b = unit(*rng);
    Eigen::Vector3d p;
    const int fixed = f < 2 ? 2 : (f < 4 ? 0 : 1);  // the face's normal axis
    const int u = fixed == 0 ? 1 : 0, v = fixed == 2 ? 1 : 2;
    p[fixed] = f % 2 == 0 ? lo[fixed] : hi[fixed];
    p[u] = lo[u] + a * size[u];
    p[v] = lo[v] + b * size[v];
    out->push_back(p);
  }
}

double DistanceToPath(const Eigen::Vector3d& p,
                      const std::vector<Eigen::Vector3d>& path) {
  double best = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& q : path) {
    best = std::min(best, (p - q).squaredNorm());
  }
  return std::sqrt(best);
}

}  // namespace

bool FlightRoomOptions::Validate(std::string* message) const {
  const struct {
    const char* name;
    double value;
  } non_negative[] = {{"wall_margin_m", wall_margin_m},
                      {"min_width_m", min_width_m},
                      {"floor_margin_m", floor_margin_m},
                      {"ceiling_margin_m", ceiling_margin_m},
                      {"landmarks_per_m2", landmarks_per_m2},
                      {"clutter_per_m3", clutter_per_m3},
                      {"clutter_clearance_m", clutter_clearance_m}};
  for (const auto& f : non_negative) {
    if (!(std::isfinite(f.value) && f.value >= 0.0)) {
      *message = std::string(f.name) + " must be >= 0 (got " +
                 std::to_string(f.value) + ")";
      return false;
    }
  }
  if (landmarks_per_m2 == 0.0 && clutter_per_m3 == 0.0) {
    *message = "landmarks_per_m2 and clutter_per_m3 are both 0: no landmarks";
    return false;
  }
  return true;
}

FlightRoom MakeFlightRoom(const std::vector<Eigen::Vector3d>& path,
                          const FlightRoomOptions& options, std::mt19937* rng) {
  std::string message;
  if (!options.Validate(&message)) {
    throw std::invalid_argument("FlightRoomOptions: " + message);
  }
  if (path.empty()) throw std::invalid_argument("MakeFlightRoom: empty path");
  Eigen::Vector3d lo = path.front(), hi = path.front();
  for (const Eigen::Vector3d& p : path) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  FlightRoom room;
  room.min_corner =
      lo - Eigen::Vector3d(options.wall_margin_m, options.wall_margin_m,
                           options.floor_margin_m);
  room.max_corner =
      hi + Eigen::Vector3d(options.wall_margin_m, options.wall_margin_m,
                           options.ceiling_margin_m);
  for (int axis = 0; axis < 2; ++axis) {
    const double grow =
        options.min_width_m - (room.max_corner[axis] - room.min_corner[axis]);
    if (grow > 0.0) {
      room.min_corner[axis] -= 0.5 * grow;
      room.max_corner[axis] += 0.5 * grow;
    }
  }
  const Eigen::Vector3d size = room.max_corner - room.min_corner;
  const double area =
      2.0 * (size.x() * size.y() + size.y() * size.z() + size.x() * size.z());
  room.surface_landmarks =
      static_cast<int>(std::lround(options.landmarks_per_m2 * area));
  AddSurface(room.min_corner, room.max_corner, room.surface_landmarks, rng,
             &room.landmarks_w);
  // Clutter: uniform in the volume, a point too close to the path redrawn
  // (at most 20 draws per point, so a room filled by the path still ends).
  const int clutter = static_cast<int>(
      std::lround(options.clutter_per_m3 * size.x() * size.y() * size.z()));
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int i = 0; i < clutter; ++i) {
    for (int attempt = 0; attempt < 20; ++attempt) {
      const double a = unit(*rng), b = unit(*rng), c = unit(*rng);
      const Eigen::Vector3d p =
          room.min_corner + Eigen::Vector3d(a, b, c).cwiseProduct(size);
      if (DistanceToPath(p, path) >= options.clutter_clearance_m) {
        room.landmarks_w.push_back(p);
        ++room.clutter_landmarks;
        break;
      }
    }
  }
  return room;
}

}  // namespace vio
