#ifndef VIO_NAVIGATION_OCCUPANCY_GRID_H_
#define VIO_NAVIGATION_OCCUPANCY_GRID_H_

// An occupancy grid of the ground plane (x-y of the gravity-aligned world)
// from the landmarks a VIO run triangulated, for planning in the place it
// mapped:
//   1. landmarks whose height z lies in the band are obstacles (the floor and
//      the ceiling are not): by default the band is the flown trajectory's
//      height range widened by band_margin_m on both sides;
//   2. a cell holding at least min_points of them is occupied;
//   3. every cell whose centre lies within radius_m of an occupied cell's
//      centre is blocked (the obstacles inflated by the robot's radius, so
//      the robot can be planned as a point);
//   4. the cells the trajectory passed through are free again: the robot
//      has been there (a landmark a few centimetres off, or the inflation,
//      must not close the way it came).
// The grid covers the trajectory and the in-band landmarks within
// max_distance_m of the trajectory's bounding box, plus radius_m and one
// cell. Cell (0, 0) is the upper-left (the largest y, the smallest x), so the
// grid reads as a map seen from above with x to the right and y up.

#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <vector>

#include "navigation/grid.h"

namespace vio {

struct OccupancyOptions {
  double cell_m = 0.1;         // cell side [m]
  double radius_m = 0.3;       // robot radius: obstacles grow by it [m]
  double band_margin_m = 0.5;  // band = trajectory z range +- this [m]
  // An explicit band [m] replaces the default when both are finite.
  double band_min_z_m = std::numeric_limits<double>::quiet_NaN();
  double band_max_z_m = std::numeric_limits<double>::quiet_NaN();
  int min_points = 1;             // landmarks in a cell to occupy it [-]
  double max_distance_m = 10.0;   // landmarks farther out are ignored [m]
  int max_cells_per_side = 4096;  // larger grids are an error [-]

  // Throws std::invalid_argument naming the field: cell_m, max_distance_m
  // > 0, radius_m, band_margin_m >= 0, band_min_z_m < band_max_z_m when
  // given, min_points >= 1, max_cells_per_side >= 16.
  void Validate() const;
};

struct OccupancyGrid {
  Grid grid;  // blocked: occupied or inflated (free again where flown)
  std::vector<uint8_t> occupied;  // row-major: >= min_points landmarks
  double cell_m = 0.1;
  double x_min_m = 0.0;  // world x of the grid's left edge [m]
  double y_max_m = 0.0;  // world y of the grid's top edge [m]
  double band_min_z_m = 0.0;
  double band_max_z_m = 0.0;
  int landmarks_in_band = 0;  // used as obstacles
  int landmarks_far = 0;      // in the band but beyond max_distance_m
  int occupied_cells = 0;
  int flown_cells_cleared = 0;  // blocked cells the trajectory freed

  // The cell holding the world point (may be off the grid: check Contains).
  Cell ToCell(const Eigen::Vector2d& xy_m) const;
  Eigen::Vector2d CellCentre(Cell c) const;
  bool Occupied(Cell c) const {
    return occupied[static_cast<size_t>(c.y) * grid.width() + c.x] != 0;
  }
};

// Builds the grid. trajectory_w holds the flown positions in order (at least
// one). Throws std::invalid_argument when the options do not validate, the
// trajectory is empty or a side would exceed max_cells_per_side.
OccupancyGrid BuildOccupancyGrid(
    const std::vector<Eigen::Vector3d>& landmarks_w,
    const std::vector<Eigen::Vector3d>& trajectory_w,
    const OccupancyOptions& options);

}  // namespace vio

#endif  // VIO_NAVIGATION_OCCUPANCY_GRID_H_
