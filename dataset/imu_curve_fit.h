#ifndef VIO_DATASET_IMU_CURVE_FIT_H_
#define VIO_DATASET_IMU_CURVE_FIT_H_

// A curve fitted to a flight's ground truth *and* its recorded IMU together
// (continuous-time batch estimation), so that the cameras vio_sim --flight
// simulates along it move as the recorded IMU says, within the IMU's noise and
// a slowly varying bias, while the ground truth corrects it at low frequency.
// The curve of dataset/trajectory_curve.h follows the ground truth alone; the
// recorded IMU then disagrees with it by far more than its noise
// (docs/recorded_flights.md, "How consistent the test is").
//
// Unknowns and residuals: dataset/imu_curve_terms.h. The fit minimises
//   sum |gyro_k|^2 / (Ng^2 dt_k)        Ng: gyroscope density, dt_k the
//                                          sample interval (the integrated
//                                          rate's noise over one interval)
//   + sum |acc_k|^2 rate / Na^2         Na: accelerometer density
//   + sum |p(t_j) - p_j|^2 / sp^2 + sum |Log(R_j^T R(t_j))|^2 / sr^2
//   + sum |b_{m+1} - b_m|^2 / (W^2 T)   W: the bias random walks, T the
//                                          bias knot spacing
//   + weak smoothness priors on the control points (as trajectory_curve.h)
// by Gauss-Newton on a sparse LDLT of the normal equations (Eigen only, like
// the ground-truth-only fit), started from control points interpolated from
// the ground truth and zero biases.

#include <cstdint>
#include <string>
#include <vector>

#include "dataset/imu_curve_terms.h"
#include "dataset/trajectory.h"
#include "dataset/trajectory_curve.h"
#include "preintegration/imu_types.h"

namespace vio {

struct ImuCurveFitOptions {
  // Knot spacing of the spline [s]: the IMU's own period (200 Hz) lets the
  // curve follow everything the IMU felt.
  double knot_spacing_s = 0.005;
  double bias_knot_spacing_s = 1.0;  // of the linear bias splines [s]
  double gravity_m_s2 = 9.81;        // g_w = (0, 0, -g) [m/s^2]
  // Ground-truth noise: 3 mm and 3 mrad, three times the ground-truth-only
  // fit's: the recorded accelerometer disagrees with EuRoC's positions by
  // the order of a centimetre over a second, and at 1 mm the curve keeps most
  // of that disagreement in the IMU (docs/recorded_flights.md, "The curve
  // fitted to the ground truth and the IMU").
  double position_sigma_m = 3e-3;    // [m]
  double rotation_sigma_rad = 3e-3;  // [rad]
  // Multipliers of the sensor.yaml white-noise densities and random walks.
  // 1: the fitted biases walk as the estimator assumes (a faster walk, 10,
  // makes the replays worse: the same document).
  double gyroscope_noise_scale = 1.0;        // [-]
  double accelerometer_noise_scale = 1.0;    // [-]
  double bias_walk_scale = 1.0;              // [-]
  double acceleration_sigma = 50.0;          // smoothness prior [m/s^2]
  double angular_acceleration_sigma = 50.0;  // smoothness prior [rad/s^2]
  int max_iterations = 10;                   // Gauss-Newton steps [-]

  // True when every value is finite and > 0 (max_iterations >= 1);
  // otherwise false with a message naming the field.
  bool Validate(std::string* message) const;
};

struct ImuCurveFitReport {
  int poses = 0;        // ground-truth poses fitted
  int imu_samples = 0;  // IMU samples inside the span
  int control_points = 0;
  int bias_knots = 0;
  int iterations = 0;
  // The curve against the ground truth.
  double position_rms_m = 0.0, position_max_m = 0.0;
  double rotation_rms_rad = 0.0, rotation_max_rad = 0.0;
  // The recorded IMU against the curve and the fitted biases, rms per axis:
  // the gyroscope as the mean rate over each sample interval.
  Eigen::Vector3d gyroscope_rms = Eigen::Vector3d::Zero();      // [rad/s]
  Eigen::Vector3d accelerometer_rms = Eigen::Vector3d::Zero();  // [m/s^2]
};

struct ImuCurveFit {
  TrajectoryCurve curve;  // the fitted spline (t = 0 at the first pose)
  ImuCurveState state;    // its unknowns, with the bias splines
  ImuCurveFitReport report;
  // The fitted biases at a stamp (held at the span's ends).
  Eigen::Vector3d GyroBiasAt(int64_t t_ns) const;
  Eigen::Vector3d AccelBiasAt(int64_t t_ns) const;
};

// poses: strictly increasing stamps spanning at least 4 knot spacings; imu:
// increasing stamps, at least 100 samples inside the poses' span; noise and
// options valid. Throws std::invalid_argument otherwise.
ImuCurveFit FitCurveToImu(const std::vector<StampedPose>& poses,
                          const std::vector<ImuSample>& imu,
                          const ImuNoise& noise,
                          const ImuCurveFitOptions& options);

}  // namespace vio

#endif  // VIO_DATASET_IMU_CURVE_FIT_H_
