#ifndef VIO_EVAL_PLOT_H_
#define VIO_EVAL_PLOT_H_

// A one-page picture of an evaluation, drawn with OpenCV and written as PNG:
//   top     the aligned estimate over the ground truth seen from above (x-y
//           plane of the ground-truth world, equal scale on both axes, grid
//           and tick labels in metres, a legend, start marked with a circle);
//   bottom  the position error [m] of each associated pose over time [s]
//           since the first one, with its RMSE as a dashed line.
// OpenCV stays inside plot.cc: this header needs only the trajectory types.

#include <string>
#include <vector>

#include "dataset/trajectory.h"

namespace vio {

struct PlotOptions {
  int width_px = 1000;   // [px] whole image
  int height_px = 1100;  // [px] whole image; the top panel takes about 2/3
  std::string title;     // first line above the top panel; may be empty
  std::string estimate_label = "estimate (aligned)";
  std::string ground_truth_label = "ground truth";
  // The bottom panel's x axis: the stamps' seconds since the first pose.
  std::string time_label = "time since first associated pose [s]";
};

// Draws the picture for associated trajectories (element i with element i)
// and writes it to `path` (PNG). error_m[i] is the position error of pose i
// [m]. Throws std::invalid_argument when the sizes differ, are 0, or the
// options ask for an image smaller than 400 x 400 px; EvalError naming the
// path when the file cannot be written.
void WriteEvaluationPlot(const std::string& path,
                         const Trajectory& ground_truth,
                         const Trajectory& aligned_estimate,
                         const std::vector<double>& error_m,
                         const PlotOptions& options = {});

}  // namespace vio

#endif  // VIO_EVAL_PLOT_H_
