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
// A still start: tau = phase + s(t) with s = 0 during still_duration, then
// a blend whose speed s' = 3 x^2 - 2 x^3 (x = time into the blend /
// blend_duration) rises smoothly from 0 to 1, so velocity and acceleration are
// continuous and the IMU has no jump; s' = 1 afterwards. With no still
// segment and no blend the sequence starts in motion at tau = phase
// (start_phase_s: where on the lap it begins).
//
// Shapes (the initialisation's degenerate motions among them):
//   ellipse   the path and attitude above (the default);
//   rotation  the ellipse's attitude, the position held at P(phase): pure
//             rotation about the IMU (the camera moves only by its lever arm);
//   line      constant velocity along +x, x = -rx + 2 rx tau / lap_period,
//             at height h, constant attitude (yaw 0, no roll or pitch): no
//             excitation at all; tau must stay within [0, lap_period];
//   circle    p = (ry cos(w tau), ry sin(w tau), h) at constant speed, heading
//             along the path, no roll or pitch: planar motion whose specific
//             force is constant in the body frame (scale unobservable).
// attitude_rate_factor multiplies the roll, pitch and yaw-sweep frequencies
// (fast rotation of a hand-held device on a small path).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>

#include "dataset/trajectory_source.h"

namespace vio {

enum class SimShape { kEllipse, kRotation, kLine, kCircle };

// "ellipse", "rotation", "line", "circle".
const char* SimShapeName(SimShape shape);
// False when `name` is none of SimShapeName's values.
bool ParseSimShape(const std::string& name, SimShape* shape);

struct SimMotionOptions {
  SimShape shape = SimShape::kEllipse;
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
  double start_phase_s = 0.0;         // tau at the start [s]
  double attitude_rate_factor = 1.0;  // on the attitude frequencies [-]

  // True when every field is finite, durations and radii are >= 0 (lap > 0),
  // amplitudes are >= 0, roll and pitch amplitudes are below 1 rad (far from
  // the Euler singularity), attitude_rate_factor > 0, start_phase_s >= 0 and
  // a still start has a blend (> 0); otherwise
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
  // Position and its tau-derivatives at tau.
  void Path(double tau, Eigen::Vector3d* P, Eigen::Vector3d* dP,
            Eigen::Vector3d* ddP) const;
  // Attitude R_w_v and body rate w_v in V [rad/s] at tau, with ds = tau'.
  void Attitude(double tau, double ds, Eigen::Matrix3d* R_w_v,
                Eigen::Vector3d* w_v) const;

  SimMotionOptions options_;
  double w_;  // lap angular frequency [rad/s]
};

}  // namespace vio

#endif  // VIO_DATASET_SIM_TRAJECTORY_H_
