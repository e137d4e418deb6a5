#ifndef VIO_NAVIGATION_POSE_FILTER_H_
#define VIO_NAVIGATION_POSE_FILTER_H_

// A smooth pose to steer by: the notes' linear Kalman filter on the
// position (x, y, z) and yaw of a body in the gravity-aligned world, each
// with its rate, under the white-acceleration model
// (navigation/white_acceleration_model.h). State (8), interleaved as in the
// notes:  x, xdot, y, ydot, z, zdot, yaw, yawdot.
// Measurement (4): x, y, z [m] and yaw [rad] of an estimated pose (vio_replay's
// output, or any trajectory). The notes' planar (X, Z, theta) is the ground-
// plane part of this with their Z as our y. Roll and pitch are not filtered:
// a controller takes them from the estimate as they are (YawOf below says
// what yaw and tilt are for any IMU mounting).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

namespace vio {

struct PoseFilterOptions {
  double position_noise_m = 0.05;        // sigma of measured x, y, z (Q_t) [m]
  double accel_noise_m_s2 = 1.0;         // k of x, y, z (R_t) [m/s^2]
  double yaw_noise_rad = 0.02;           // sigma of measured yaw (Q_t) [rad]
  double yaw_accel_noise_rad_s2 = 1.0;   // k of yaw (R_t) [rad/s^2]
  double initial_speed_sigma_m_s = 1.0;  // first state's rates [m/s]
  double initial_yaw_rate_sigma_rad_s = 1.0;  // [rad/s]

  // Throws std::invalid_argument naming the field unless every value is
  // finite and > 0.
  void Validate() const;
};

// Slots of the state (no magic offsets).
constexpr int kFilterX = 0, kFilterY = 2, kFilterZ = 4, kFilterYaw = 6;
constexpr int kFilterStateSize = 8;

struct PoseMeasurement {
  int64_t t_ns = 0;
  Eigen::Vector3d p_w = Eigen::Vector3d::Zero();  // [m]
  double yaw_rad = 0.0;
};

struct FilteredPose {
  int64_t t_ns = 0;
  Eigen::Vector3d p_w = Eigen::Vector3d::Zero();  // [m]
  double yaw_rad = 0.0;                           // in (-pi, pi]
  Eigen::Vector3d v_w = Eigen::Vector3d::Zero();  // [m/s]
  double yaw_rate_rad_s = 0.0;
  double nis = 0.0;  // of this update (0 for the first pose) [-]
};

class PoseFilter {
 public:
  // Throws std::invalid_argument when the options do not validate.
  explicit PoseFilter(const PoseFilterOptions& options);

  // Predicts to the measurement's stamp and updates with it; the first call
  // starts the filter at the measurement (rates 0). Throws
  // std::invalid_argument unless stamps strictly increase and values are
  // finite.
  FilteredPose Add(const PoseMeasurement& z);

  // The state predicted dt_s [s] past the last update (latency
  // compensation), without changing the filter. Requires a first Add.
  FilteredPose PredictAhead(double dt_s) const;

  // The state's covariance after the last Add (8x8, slots above).
  const Eigen::MatrixXd& covariance() const;

 private:
  FilteredPose Output(const Eigen::VectorXd& x, int64_t t_ns, double nis) const;

  PoseFilterOptions options_;
  bool started_ = false;
  int64_t t_ns_ = 0;
  Eigen::VectorXd mu_;
  Eigen::MatrixXd sigma_;
};

// Heading of a body [rad], in (-pi, pi]: the angle of the twist about the
// world z axis in the swing-twist split q_w_b = Rz(yaw) * q_swing, where
// q_swing turns about a horizontal axis. It is 2 atan2(q.z, q.w). Unlike the
// Z-Y-X (yaw, pitch, roll) yaw, which is singular when the body's x axis is
// vertical (EuRoC's IMU is mounted x up), it is defined for every attitude
// but a half turn about a horizontal axis (q.z = q.w = 0; then 0). For a
// level body it is the Z-Y-X yaw. YawOf(Rz(d) * q) = YawOf(q) + d.
double YawOf(const Eigen::Quaterniond& q_w_b);

// q_w_b with its heading replaced and its tilt (q_swing: roll and pitch)
// kept: Rz(yaw - YawOf(q)) * q.
Eigen::Quaterniond WithYaw(const Eigen::Quaterniond& q_w_b, double yaw_rad);

}  // namespace vio

#endif  // VIO_NAVIGATION_POSE_FILTER_H_
