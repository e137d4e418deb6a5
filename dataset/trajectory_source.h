#ifndef VIO_DATASET_TRAJECTORY_SOURCE_H_
#define VIO_DATASET_TRAJECTORY_SOURCE_H_

// Where the simulator's true motion comes from: anything that can give the
// body's state, with exact first and second derivatives, at a time. The
// built-in presets use the analytic SimTrajectory (dataset/sim_trajectory.h);
// a recorded flight uses the curve fitted to its ground truth
// (dataset/trajectory_curve.h).

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace vio {

// The true state at one instant.
struct SimState {
  Eigen::Vector3d p_w_b;  // position [m]
  Eigen::Vector3d v_w;    // velocity in W [m/s]
  Eigen::Vector3d a_w;    // acceleration in W [m/s^2]
  Eigen::Quaterniond q_w_b;
  Eigen::Vector3d w_b;  // angular rate in B [rad/s]
};

class TrajectorySource {
 public:
  virtual ~TrajectorySource() = default;

  // The state at `t` seconds after the simulation's start
  // (SimulatorOptions::start_time_ns). v_w, a_w and w_b are the analytic
  // derivatives of p_w_b and q_w_b, so the IMU computed from them integrates
  // back to the trajectory.
  virtual SimState At(double t) const = 0;
};

}  // namespace vio

#endif  // VIO_DATASET_TRAJECTORY_SOURCE_H_
