#ifndef VIO_DATASET_IMU_CURVE_RESIDUAL_H_
#define VIO_DATASET_IMU_CURVE_RESIDUAL_H_

// How a recorded IMU agrees with the curve fitted to the flight's ground
// truth (dataset/trajectory_curve.h): the test of vio_sim --flight --imu
// recorded is only as consistent as that agreement, because the cameras are
// simulated from the curve while the IMU felt the true motion. Whatever
// separates the two (a clock offset between the ground truth and imu0, ground
// truth errors, motion the curve cannot follow) reaches the estimator as IMU
// error that no estimator can remove.
//
// For a sample stamped t and a trial offset d the residuals are
//   r_g(t) = gyr(t) - w_b(t + d)
//   r_a(t) = acc(t) - R_w_b(t + d)^T (a_w(t + d) - g_w),   g_w = (0, 0, -g)
// (w_b, R_w_b, a_w: the curve's body rate, attitude and acceleration). The
// offset d that minimises the rms of r_g (each axis with its moving average
// over bias_window_s removed, so that the slowly varying bias does not count)
// is the offset that best aligns the recorded gyroscope with the curve: the
// IMU sample stamped t saw the motion the ground truth stamps t + d. The same
// is done for the accelerometer on its own.
//
// The Allan deviation of the residuals at offset d tells how the disagreement
// behaves with the averaging time tau: white noise of density N gives
// adev(tau) = N / sqrt(tau), i.e. an equivalent density adev(tau) sqrt(tau)
// that does not depend on tau; a rising equivalent density means coloured
// error (vibration aliased to low frequencies, ground-truth errors, bias
// changes) that a white-noise model underrates over a preintegration interval.

#include <vector>

#include <Eigen/Core>

#include "dataset/trajectory_curve.h"
#include "preintegration/imu_types.h"

namespace vio {

struct ImuCurveResidualOptions {
  double gravity_m_s2 = 9.81;    // g [m/s^2]
  double max_offset_s = 0.05;    // offsets searched in [-max, max] [s]
  double coarse_step_s = 1e-3;   // grid of the search [s]
  double fine_step_s = 5e-5;     // refinement around the grid's best [s]
  double bias_window_s = 5.0;    // moving average removed from r [s]
  // Averaging times of the Allan deviation [s].
  std::vector<double> allan_tau_s = {0.005, 0.01, 0.02, 0.05, 0.1,
                                     0.2,   0.5,  1.0,  2.0,  5.0};
};

// The Allan deviation of both residuals at one averaging time.
struct AllanPoint {
  double tau_s = 0.0;
  Eigen::Vector3d gyr = Eigen::Vector3d::Zero();  // [rad/s], per axis
  Eigen::Vector3d acc = Eigen::Vector3d::Zero();  // [m/s^2], per axis
};

struct ImuCurveResidual {
  int samples = 0;                 // IMU samples compared
  double gyr_offset_s = 0.0;       // best d for the gyroscope [s]
  double acc_offset_s = 0.0;       // best d for the accelerometer [s]
  // Rms of the bias-removed residuals per axis, at d = 0 and at the
  // gyroscope's best d (the offset a correction would apply).
  Eigen::Vector3d gyr_rms_at_zero = Eigen::Vector3d::Zero();   // [rad/s]
  Eigen::Vector3d acc_rms_at_zero = Eigen::Vector3d::Zero();   // [m/s^2]
  Eigen::Vector3d gyr_rms_at_best = Eigen::Vector3d::Zero();   // [rad/s]
  Eigen::Vector3d acc_rms_at_best = Eigen::Vector3d::Zero();   // [m/s^2]
  double sample_rate_hz = 0.0;     // of the IMU, from its stamps
  std::vector<AllanPoint> allan;   // at the gyroscope's best d
};

// The residuals of the samples of `imu` whose stamps lie at least
// max_offset_s inside the curve's span (so that every trial offset compares
// the same samples). Throws std::invalid_argument when fewer than 100 samples
// are left or the options are not positive.
ImuCurveResidual CompareImuWithCurve(const TrajectoryCurve& curve,
                                     const std::vector<ImuSample>& imu,
                                     const ImuCurveResidualOptions& options);

}  // namespace vio

#endif  // VIO_DATASET_IMU_CURVE_RESIDUAL_H_
