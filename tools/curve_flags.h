#ifndef VIO_TOOLS_CURVE_FLAGS_H_
#define VIO_TOOLS_CURVE_FLAGS_H_

// The flags that choose a flight's curve and set the joint fit's options
// (dataset/imu_curve_fit.h), shared by vio_sim and vio_imu_check so the two
// read them alike.

#include <stdexcept>
#include <string>

#include "dataset/flight_simulation.h"
#include "dataset/imu_curve_fit.h"
#include "tools/command_line.h"

namespace vio {

// Takes the current flag when it is --curve or one of --fit-*: sets *curve or
// *options from its value and returns true; returns false for any other flag.
// Throws std::invalid_argument naming the flag on a bad value.
inline bool ParseCurveFlag(CommandLine& line, FlightCurve* curve,
                           ImuCurveFitOptions* options) {
  const std::string& flag = line.Current();
  if (flag == "--curve") {
    const std::string fit = line.Value();
    if (fit == "ground-truth") {
      *curve = FlightCurve::kGroundTruth;
    } else if (fit == "imu") {
      *curve = FlightCurve::kGroundTruthAndImu;
    } else {
      throw std::invalid_argument("--curve expects ground-truth or imu (got '" +
                                  fit + "')");
    }
  } else if (flag == "--fit-noise-scale") {
    const double scale = line.Number<double>();
    options->gyroscope_noise_scale = scale;
    options->accelerometer_noise_scale = scale;
  } else if (flag == "--fit-bias-walk-scale") {
    options->bias_walk_scale = line.Number<double>();
  } else if (flag == "--fit-bias-knot-spacing") {
    options->bias_knot_spacing_s = line.Number<double>();
  } else if (flag == "--fit-position-sigma") {
    options->position_sigma_m = line.Number<double>();
  } else if (flag == "--fit-rotation-sigma") {
    options->rotation_sigma_rad = line.Number<double>();
  } else if (flag == "--fit-knot-spacing") {
    options->knot_spacing_s = line.Number<double>();
  } else {
    return false;
  }
  return true;
}

}  // namespace vio

#endif  // VIO_TOOLS_CURVE_FLAGS_H_
