#ifndef VIO_DATASET_SIM_TRAJECTORY_H_
#define VIO_DATASET_SIM_TRAJECTORY_H_

// The simulator's analytic body trajectory, with exact first and second
// derivatives so that IMU samples can be computed, not differenced.
//
// Path, in a motion parameter tau [s]:
//   p(tau) = (rx cos(w tau), ry sin(w tau), h + A_h sin(2 w tau)),
//   w = 2 pi / lap_period: an ellipse around the room's centre whose height
//   rises and falls twice per lap.
// Attitude of a vehicle frame V (x forward, y left, z up), Z-Y-X Euler angles:
//   yaw   = w tau + pi/2 + A_yaw sin(1.3 w tau)  (heading along the path, plus
//                                                  a sweep of the view)
//   pitch = A_pitch sin(2.3 w tau),  roll = A_roll sin(1.7 w tau)
//   (frequencies incommensurate with the lap so that every axis is excited).
// The body (IMU) frame is mounted as EuRoC's VI-Sensor: x up, z forward
// (R_v_b = [[0,0,1],[0,-1,0],[1,0,0]]), so at rest the accelerometer reads
// about (+9.81, 0, 0) and EuRoC's camera extrinsics look forward.
//
// A still start: tau = s(t) with s = 0 during still_duration, then a blend
// whose speed s' = 3 x^2 - 2 x^3 (x = time into the blend / blend_duration)
// rises smoothly from 0 to 1, so velocity and acceleration are continuous and
// the IMU has no jump; s' = 1 afterwards.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>

#include "dataset/trajectory_source.h"

namespace vio {

struct SimMotionOptions {
  double still_duration_s = 2.0;      // at rest at the start [s]
  double blend_duration_s = 2.0;      // ramp from rest to full speed [s]
  double radius_x_m = 3.0;            // ellipse semi-axis along x [m]
  double radius_y_m = 2.0;            // ellipse semi-axis along y [m]
  double lap_period_s = 15.0;         // one lap at full speed [s]
  double height_m = 1.2;              // mean height above the floor [m]
  double height_amplitude_m = 0.4;    // [m]
  double roll_amplitude_rad = 0.15;   // [rad]
  double pitch_amplitude_rad = 0.15;  // [rad]
  double yaw_amplitude_rad = 0.3;     // sweep around the path heading [rad]

  // True when every field is finite, durations and radii are >= 0 (lap > 0),
  // amplitudes are >= 0, roll and pitch amplitudes are below 1 rad (far from
  // the Euler singularity) and a still start has a blend (> 0); otherwise
  // false with a message that starts with the offending field's name.
  bool Validate(std::string* message) const;
};

class SimTrajectory : public TrajectorySource {
 public:
  // `options` must be valid (Validate()); throws std::invalid_argument if not.
  explicit SimTrajectory(const SimMotionOptions& options);

  // The state at `t` seconds after the start. Before the start it is the
  // still pose when there is a still start or blend, else the analytic path
  // continued backwards.
  SimState At(double t) const override;

  const SimMotionOptions& options() const { return options_; }

 private:
  SimMotionOptions options_;
  double w_;  // lap angular frequency [rad/s]
};

}  // namespace vio

#endif  // VIO_DATASET_SIM_TRAJECTORY_H_
