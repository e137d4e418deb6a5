#ifndef VIO_TOOLS_CURVE_FITTING_CURVE_PLOT_H_
#define VIO_TOOLS_CURVE_FITTING_CURVE_PLOT_H_

// A PNG of the curve fitting exercise (OpenCV): the samples (outliers marked),
// the true curve and both fits, on axes with ticks and a legend.

#include <Eigen/Core>
#include <string>

#include "tools/curve_fitting/curve_problem.h"

namespace vio {

struct CurvePlot {
  const CurveSamples* samples = nullptr;  // not owned, must be set
  Eigen::Vector3d truth = Eigen::Vector3d::Zero();
  Eigen::Vector3d ceres_fit = Eigen::Vector3d::Zero();
  Eigen::Vector3d lm_fit = Eigen::Vector3d::Zero();
  std::string title;
};

// Draws the plot and writes it to path (PNG, 1000 x 650 px). Throws
// std::runtime_error naming the file when it cannot be written.
void WriteCurvePlot(const std::string& path, const CurvePlot& plot);

}  // namespace vio

#endif  // VIO_TOOLS_CURVE_FITTING_CURVE_PLOT_H_
