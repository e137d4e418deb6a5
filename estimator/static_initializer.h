#ifndef VIO_ESTIMATOR_STATIC_INITIALIZER_H_
#define VIO_ESTIMATOR_STATIC_INITIALIZER_H_

// Initialisation from a static start: while the vehicle stands still the
// accelerometer measures only gravity and its bias, a_m = R_w_b^T (0, 0, g) +
// b_a, and the gyroscope only its bias, w_m = b_g. Averaging over a still span
// gives the attitude up to yaw (yaw is unobservable; it is set to 0) and the
// gyroscope bias. Of the accelerometer bias only the component along gravity
// shows (|a_m| - g); the rest is indistinguishable from a tilt.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <deque>
#include <vector>

#include "estimator/estimator_options.h"
#include "preintegration/imu_types.h"

namespace vio {

// Mean and per-axis standard deviations of a span of IMU samples. A MAV on the
// ground with its rotors running vibrates: EuRoC V1_01 shows a raw
// accelerometer std of 0.6 m/s^2 while standing. Motion is slow beside that,
// so stillness is judged on the std of short block means (a low-pass).
struct ImuStatistics {
  int count = 0;
  double duration_s = 0.0;                             // last - first [s]
  Eigen::Vector3d acc_mean = Eigen::Vector3d::Zero();  // [m/s^2]
  Eigen::Vector3d gyr_mean = Eigen::Vector3d::Zero();  // [rad/s]
  Eigen::Vector3d acc_std = Eigen::Vector3d::Zero();   // [m/s^2]
  Eigen::Vector3d gyr_std = Eigen::Vector3d::Zero();   // [rad/s]
  // Std of the means of consecutive blocks of block_s seconds.
  Eigen::Vector3d acc_block_std = Eigen::Vector3d::Zero();  // [m/s^2]
  Eigen::Vector3d gyr_block_std = Eigen::Vector3d::Zero();  // [rad/s]
  int blocks = 0;
};

// Statistics of the samples, in time order; blocks of block_s [s] start at
// the first sample (a trailing partial block is left out of the block std).
// Empty input gives count 0 and zeros.
ImuStatistics ComputeImuStatistics(const std::vector<ImuSample>& samples,
                                   double block_s);

// The initial state a static start gives.
struct StaticInitState {
  Eigen::Quaterniond q_w_b = Eigen::Quaterniond::Identity();  // yaw 0
  Eigen::Vector3d b_a = Eigen::Vector3d::Zero();              // [m/s^2]
  Eigen::Vector3d b_g = Eigen::Vector3d::Zero();              // [rad/s]
};

// The attitude with yaw 0 that maps the measured specific force direction
// (body frame) onto +z of the world: R_w_b * f_b / |f_b| = (0, 0, 1).
// Precondition: f_b is finite and not zero (std::invalid_argument otherwise).
Eigen::Quaterniond GravityAlignedAttitude(const Eigen::Vector3d& f_b);

// Yaw of a rotation [rad] (z-y-x Euler angles).
double Yaw(const Eigen::Matrix3d& R_w_b);

// Collects IMU samples and decides when the last options.window_s seconds are
// still enough to initialise.
class StaticInitializer {
 public:
  StaticInitializer(const StaticInitOptions& options, double gravity_magnitude)
      : options_(options), gravity_magnitude_(gravity_magnitude) {}

  // Appends a sample; older samples than the window are dropped. Non-finite
  // samples must be filtered by the caller.
  void AddSample(const ImuSample& sample);

  // True when the buffered samples span at least the window and their block
  // standard deviations are below the stillness limits; then fills *state
  // (with b_a from the residual along gravity when the options ask).
  bool TryInitialize(StaticInitState* state) const;

  // The statistics of the current buffer (for logs and tests).
  ImuStatistics Statistics() const;

  void Clear() { samples_.clear(); }

 private:
  StaticInitOptions options_;
  double gravity_magnitude_;
  std::deque<ImuSample> samples_;
};

}  // namespace vio

#endif  // VIO_ESTIMATOR_STATIC_INITIALIZER_H_
