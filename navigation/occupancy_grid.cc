#include "navigation/occupancy_grid.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace vio {
namespace {

void Require(bool ok, const std::string& message) {
  if (!ok) throw std::invalid_argument("OccupancyOptions: " + message);
}

struct Box {
  Eigen::Vector2d lo{1e300, 1e300};
  Eigen::Vector2d hi{-1e300, -1e300};
  void Add(const Eigen::Vector2d& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  // Distance [m] from the box (0 inside).
  double Distance(const Eigen::Vector2d& p) const {
    return (p - p.cwiseMax(lo).cwiseMin(hi)).norm();
  }
};

void SetFree(OccupancyGrid* g, Cell c) {
  if (!g->grid.Contains(c) || !g->grid.Blocked(c)) return;
  g->grid.SetBlocked(c, false);
  ++g->flown_cells_cleared;
}

// Frees the cells along the polyline, sampled at a quarter cell.
void ClearFlownCells(const std::vector<Eigen::Vector3d>& trajectory_w,
                     OccupancyGrid* g) {
  SetFree(g, g->ToCell(trajectory_w.front().head<2>()));
  for (size_t i = 1; i < trajectory_w.size(); ++i) {
    const Eigen::Vector2d a = trajectory_w[i - 1].head<2>();
    const Eigen::Vector2d b = trajectory_w[i].head<2>();
    const int steps =
        1 + static_cast<int>(std::ceil((b - a).norm() / (0.25 * g->cell_m)));
    for (int s = 1; s <= steps; ++s) {
      SetFree(g, g->ToCell(a + (b - a) * (static_cast<double>(s) / steps)));
    }
  }
}

}  // namespace

void OccupancyOptions::Validate() const {
  Require(cell_m > 0.0 && std::isfinite(cell_m), "cell_m must be > 0 [m]");
  Require(radius_m >= 0.0 && std::isfinite(radius_m),
          "radius_m must be >= 0 [m]");
  Require(band_margin_m >= 0.0 && std::isfinite(band_margin_m),
          "band_margin_m must be >= 0 [m]");
  const bool given = std::isfinite(band_min_z_m) || std::isfinite(band_max_z_m);
  Require(
      !given || (std::isfinite(band_min_z_m) && std::isfinite(band_max_z_m) &&
                 band_min_z_m < band_max_z_m),
      "band_min_z_m < band_max_z_m, both finite, when a band is given");
  Require(min_points >= 1, "min_points must be >= 1");
  Require(max_distance_m > 0.0, "max_distance_m must be > 0 [m]");
  Require(max_cells_per_side >= 16, "max_cells_per_side must be >= 16");
}

Cell OccupancyGrid::ToCell(const Eigen::Vector2d& xy) const {
  return {static_cast<int>(std::floor((xy.x() - x_min_m) / cell_m)),
          static_cast<int>(std::floor((y_max_m - xy.y()) / cell_m))};
}

Eigen::Vector2d OccupancyGrid::CellCentre(Cell c) const {
  return {x_min_m + (c.x + 0.5) * cell_m, y_max_m - (c.y + 0.5) * cell_m};
}

OccupancyGrid BuildOccupancyGrid(
    const std::vector<Eigen::Vector3d>& landmarks_w,
    const std::vector<Eigen::Vector3d>& trajectory_w,
    const OccupancyOptions& o) {
  o.Validate();
  if (trajectory_w.empty()) {
    throw std::invalid_argument("BuildOccupancyGrid: empty trajectory");
  }
  OccupancyGrid g;
  g.cell_m = o.cell_m;
  Box flown;
  double z_lo = 1e300, z_hi = -1e300;
  for (const Eigen::Vector3d& p : trajectory_w) {
    flown.Add(p.head<2>());
    z_lo = std::min(z_lo, p.z());
    z_hi = std::max(z_hi, p.z());
  }
  const bool explicit_band = std::isfinite(o.band_min_z_m);
  g.band_min_z_m = explicit_band ? o.band_min_z_m : z_lo - o.band_margin_m;
  g.band_max_z_m = explicit_band ? o.band_max_z_m : z_hi + o.band_margin_m;

  std::vector<Eigen::Vector2d> obstacles;
  Box extent = flown;
  for (const Eigen::Vector3d& l : landmarks_w) {
    if (!l.allFinite() || l.z() < g.band_min_z_m || l.z() > g.band_max_z_m) {
      continue;
    }
    if (flown.Distance(l.head<2>()) > o.max_distance_m) {
      ++g.landmarks_far;
      continue;
    }
    obstacles.push_back(l.head<2>());
    extent.Add(l.head<2>());
  }
  g.landmarks_in_band = static_cast<int>(obstacles.size());

  const double pad = o.radius_m + o.cell_m;
  const Eigen::Vector2d size =
      extent.hi - extent.lo + Eigen::Vector2d::Constant(2.0 * pad);
  const double cells_x = std::ceil(size.x() / o.cell_m);
  const double cells_y = std::ceil(size.y() / o.cell_m);
  if (cells_x > o.max_cells_per_side || cells_y > o.max_cells_per_side) {
    throw std::invalid_argument(
        "BuildOccupancyGrid: the grid would be " +
        std::to_string(static_cast<long>(cells_x)) + " x " +
        std::to_string(static_cast<long>(cells_y)) + " cells (at most " +
        std::to_string(o.max_cells_per_side) + " a side): use larger cells");
  }
  g.grid = Grid(static_cast<int>(cells_x), static_cast<int>(cells_y));
  g.x_min_m = extent.lo.x() - pad;
  g.y_max_m = extent.hi.y() + pad;
  const int w = g.grid.width();
  const int h = g.grid.height();

  std::vector<int> count(static_cast<size_t>(w) * h, 0);
  for (const Eigen::Vector2d& p : obstacles) {
    const Cell c = g.ToCell(p);
    if (g.grid.Contains(c)) ++count[static_cast<size_t>(c.y) * w + c.x];
  }
  g.occupied.assign(count.size(), 0);
  // The disc of cells whose centres lie within radius_m of a cell's centre.
  // (+1e-9: 0.3 / 0.1 is 2.9999999999999996 in doubles.)
  const int r = static_cast<int>(std::floor(o.radius_m / o.cell_m + 1e-9));
  std::vector<Cell> disc;
  for (int dy = -r; dy <= r; ++dy) {
    for (int dx = -r; dx <= r; ++dx) {
      if (std::hypot(dx, dy) * o.cell_m <= o.radius_m + 1e-9) {
        disc.push_back({dx, dy});
      }
    }
  }
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      if (count[static_cast<size_t>(y) * w + x] < o.min_points) continue;
      g.occupied[static_cast<size_t>(y) * w + x] = 1;
      ++g.occupied_cells;
      for (const Cell& d : disc) {
        const Cell c{x + d.x, y + d.y};
        if (g.grid.Contains(c)) g.grid.SetBlocked(c, true);
      }
    }
  }
  ClearFlownCells(trajectory_w, &g);
  return g;
}

}  // namespace vio
