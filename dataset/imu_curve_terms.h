#ifndef VIO_DATASET_IMU_CURVE_TERMS_H_
#define VIO_DATASET_IMU_CURVE_TERMS_H_

// The residuals of the curve fitted to a flight's ground truth *and* its
// recorded IMU (dataset/imu_curve_fit.h), each with its analytic Jacobian.
//
// Unknowns (ImuCurveState): the control points of a uniform cubic B-spline
// (geometry/pose_spline.h; positions c_i and rotations R_i, knots dt apart
// from t = 0) and the knots of two linear bias splines
//   b(t) = (1 - l) b_m + l b_{m+1},  m = floor(t / T), l = t / T - m,
// for the gyroscope (b_g) and the accelerometer (b_a), T the bias knot
// spacing. Every unknown is a 3-vector "block": block 2i is c_i, 2i + 1 is
// R_i, then 2n + 2m is b_g,m and 2n + 2m + 1 is b_a,m (n control points).
// Perturbations: c (+) d = c + d, R (+) d = R Exp(d) (the project's right
// perturbation), b (+) d = b + d.
//
// Residuals (not whitened: the fit divides by the noise):
//   gyroscope over [t_a, t_b]:   Log(R(t_a)^T R(t_b)) - (w_mean - b_g(t_m)) dt,
//                                t_m = (t_a + t_b) / 2, dt = t_b - t_a
//   accelerometer at t:          R(t)^T (a(t) - g_w) + b_a(t) - acc
//   ground-truth position at t:  p(t) - p
//   ground-truth rotation at t:  Log(R^T R(t))
//   smoothness of the control points (weak priors):
//     c_{i-1} - 2 c_i + c_{i+1};  d_{i+1} - d_i, d_i = Log(R_i^T R_{i+1})
//   bias walk:                   b_{m+1} - b_m
// The gyroscope is compared as a rotation increment over one sample interval
// (midpoint rate, as the preintegration integrates it), which needs only the
// Jacobian of R(t), not that of the body rate.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "geometry/pose_spline.h"

namespace vio {

struct ImuCurveState {
  double knot_spacing_s = 0.005;
  std::vector<Eigen::Vector3d> positions;     // c_i [m]
  std::vector<Eigen::Quaterniond> rotations;  // R_i (q_w_b)
  double bias_knot_spacing_s = 1.0;
  std::vector<Eigen::Vector3d> b_g;  // gyroscope bias knots [rad/s]
  std::vector<Eigen::Vector3d> b_a;  // accelerometer bias knots [m/s^2]

  int control_points() const { return static_cast<int>(positions.size()); }
  int bias_knots() const { return static_cast<int>(b_g.size()); }
  int blocks() const { return 2 * control_points() + 2 * bias_knots(); }
  int PositionBlock(int i) const { return 2 * i; }
  int RotationBlock(int i) const { return 2 * i + 1; }
  int GyroBiasBlock(int m) const { return 2 * control_points() + 2 * m; }
  int AccelBiasBlock(int m) const { return 2 * control_points() + 2 * m + 1; }

  PoseSpline Spline() const;
  // The bias knot m and weight l of time t (clamped to the knots' span).
  void BiasKnot(double t, int* m, double* l) const;
  Eigen::Vector3d GyroBias(double t) const;
  Eigen::Vector3d AccelBias(double t) const;
  // Applies the perturbation d to one block (see the header).
  void Plus(int block, const Eigen::Vector3d& d);
};

// One residual, linearised: r and d r / d (blocks), three columns per block.
struct CurveTerm {
  Eigen::VectorXd r;
  Eigen::MatrixXd J;
  std::vector<int> blocks;
};

// `spline` is state.Spline() (passed so that it is built once per
// linearisation); times in seconds from the spline's start, inside its span.
CurveTerm GyroIntervalTerm(const ImuCurveState& state, const PoseSpline& spline,
                           double t_a, double t_b,
                           const Eigen::Vector3d& w_mean_rad_s);
CurveTerm AccelerometerTerm(const ImuCurveState& state,
                            const PoseSpline& spline, double t,
                            const Eigen::Vector3d& acc_m_s2,
                            double gravity_m_s2);
CurveTerm PositionTerm(const ImuCurveState& state, const PoseSpline& spline,
                       double t, const Eigen::Vector3d& p_w_b);
CurveTerm RotationTerm(const ImuCurveState& state, const PoseSpline& spline,
                       double t, const Eigen::Quaterniond& q_w_b);
// Smoothness around control point i (1 <= i <= n - 2).
CurveTerm PositionSmoothnessTerm(const ImuCurveState& state, int i);
CurveTerm RotationSmoothnessTerm(const ImuCurveState& state, int i);
// b_{m+1} - b_m of the gyroscope (gyro = true) or accelerometer bias.
CurveTerm BiasWalkTerm(const ImuCurveState& state, int m, bool gyro);

}  // namespace vio

#endif  // VIO_DATASET_IMU_CURVE_TERMS_H_
