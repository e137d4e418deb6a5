#ifndef VIO_NAVIGATION_NAVIGATION_PLOT_H_
#define VIO_NAVIGATION_NAVIGATION_PLOT_H_

// The navigation layer's PNG pictures, drawn with OpenCV. OpenCV stays inside
// navigation_plot.cc: this header needs only Eigen and the grid types.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "navigation/occupancy_grid.h"

namespace vio {

// One labelled curve: points in the panel's units, drawn in palette colour
// `colour` (0 grey, 1 blue, 2 red, 3 green, 4 orange) as a line of
// `thickness` px, or as dots when thickness is 0.
struct PlotCurve {
  std::string label;
  std::vector<Eigen::Vector2d> points;
  int colour = 1;
  int thickness = 1;
};

// vio_filter's picture: on top the curves seen from above (x-y [m], equal
// scale), below the curves of a quantity over time (time [s], y_label).
// Throws std::invalid_argument when top has no point; NavigationError naming
// the path when the file cannot be written.
void WriteFilterPlot(const std::string& path, const std::string& title,
                     const std::vector<PlotCurve>& top,
                     const std::string& y_label,
                     const std::vector<PlotCurve>& bottom);

// vio_plan --replay's picture: the grid (occupied cells dark, inflated cells
// light, free white), the landmarks used (orange dots), the trajectory
// (blue), the planned path (red, empty when none), the start (circle) and the
// goal (square), with x-y ticks in metres. NavigationError when the file
// cannot be written.
void WritePlanPlot(const std::string& path, const std::string& title,
                   const OccupancyGrid& grid,
                   const std::vector<Eigen::Vector2d>& landmarks_xy,
                   const std::vector<Eigen::Vector2d>& trajectory_xy,
                   const std::vector<Eigen::Vector2d>& path_xy,
                   const Eigen::Vector2d& start_xy,
                   const Eigen::Vector2d& goal_xy);

}  // namespace vio

#endif  // VIO_NAVIGATION_NAVIGATION_PLOT_H_
