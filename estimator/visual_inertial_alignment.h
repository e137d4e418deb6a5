#ifndef VIO_ESTIMATOR_VISUAL_INERTIAL_ALIGNMENT_H_
#define VIO_ESTIMATOR_VISUAL_INERTIAL_ALIGNMENT_H_

// Visual-inertial alignment: a visual trajectory (attitudes and camera
// positions in a frame v of its own, up to scale for a monocular one) and the
// IMU preintegrated between its frames give the gyroscope bias, the
// velocities, gravity in v and the metric scale (Qin et al., "VINS-Mono",
// T-RO 2018, sec. V-B; Mur-Artal and Tardos, "Visual-inertial monocular SLAM
// with map reuse", RA-L 2017, sec. IV).
//
// Frames k = 0..n-1 with body attitude R_k = R_v_bk, camera-0 position
// pbar_k (visual units), extrinsic t_b_c, stamps t_k. Since
// p_v_bk = s pbar_k - R_k t_b_c and the IMU kinematics in v read
//   p_k = p_0 + v_0 T_k + g T_k^2 / 2 + R_0 dp_0k,   T_k = t_k - t_0,
// with dp_0k preintegrated from frame 0 to frame k (in the body frame at 0),
// every frame k > 0 gives three equations linear in x = (v_0, g, s, db_a):
//   s (pbar_k - pbar_0) - T_k v_0 - T_k^2/2 g - R_0 J_k db_a
//       = R_0 dp_0k + (R_k - R_0) t_b_c
// (J_k = d dp_0k / d b_a), and the velocities follow as
//   v_k = v_0 + g T_k + R_0 (dv_0k + d dv_0k / d b_a db_a).
// Why from frame 0 and not interval by interval as VINS-Mono writes it (with
// one velocity unknown per frame): then the scale is fixed by the second
// differences of positions 0.1-0.2 s apart, a few millimetres of
// acceleration, and millimetres of visual position noise, sitting in the
// scale's own column (errors in variables), bias it low by tens of percent;
// from frame 0 the acceleration shows over the whole span (decimetres).
// The accelerometer bias, which an unknown 0.075 m/s^2 of moves the scale by
// ~10 % over 1.5 s of gentle motion, is estimated with a Gaussian prior.

#include <Eigen/Core>
#include <vector>

#include "preintegration/imu_preintegration.h"

namespace vio {

// One frame of the visual trajectory.
struct AlignmentFrame {
  Eigen::Matrix3d R_v_b = Eigen::Matrix3d::Identity();  // body attitude in v
  Eigen::Vector3d p_v_c = Eigen::Vector3d::Zero();  // camera 0 [visual units]
};

// The gyroscope bias that makes the preintegrated rotations agree with the
// visual ones: with r_k = Log(dq_k^-1 R_k^T R_{k+1}) and dq_k(b_g + d) ~
// dq_k Exp(J_k d) (J_k = d_dq_d_bg), minimises sum |r_k - J_k d|^2 by the
// normal equations, re-propagates every interval with (b_a, the new bias) and
// repeats `iterations` times. intervals[k] runs from frames[k] to frames[k+1].
// Returns the bias [rad/s].
Eigen::Vector3d AlignGyroscopeBias(const std::vector<AlignmentFrame>& frames,
                                   const Eigen::Vector3d& b_a,
                                   std::vector<ImuPreintegration>* intervals,
                                   int iterations = 2);

// The RMS of r_k over the intervals at their current biases [rad].
double RotationMisfitRms(const std::vector<AlignmentFrame>& frames,
                         const std::vector<ImuPreintegration>& intervals);

struct AlignmentOptions {
  bool estimate_scale = true;  // false: a metric trajectory, s = 1
  // The accelerometer bias is estimated about the given one with a prior of
  // this standard deviation [m/s^2]; 0 holds it at the given one.
  double accel_bias_sigma = 0.2;
  // Standard deviation of the visual positions, which weighs the equations
  // against that prior [m].
  double position_sigma_m = 0.01;
};

// The solution of the linear alignment.
struct VelocityGravityScale {
  std::vector<Eigen::Vector3d> v_v;               // per frame, in v [m/s]
  Eigen::Vector3d g_v = Eigen::Vector3d::Zero();  // gravity in v [m/s^2]
  double scale = 1.0;  // metres per visual unit (1 when not estimated)
  // Standard deviation of the scale from the least-squares covariance,
  // sigma^2 (A^T A)^-1 with sigma^2 = |A x - b|^2 / (rows - unknowns) [m/unit];
  // 0 when the scale is not estimated.
  double scale_sigma = 0.0;
  Eigen::Vector3d b_a = Eigen::Vector3d::Zero();  // estimated [m/s^2]
  double residual_rms = 0.0;  // of the position equations [m]
  // Standard deviation of |g_v| from the same covariance, g_hat^T Cov_g g_hat
  // (SolveVelocityGravityScale only; RefineGravity holds |g|) [m/s^2].
  double gravity_norm_sigma = 0.0;
};

// Solves the system above for v_0, gravity (free magnitude), the scale (with
// options.estimate_scale; otherwise s = 1) and the accelerometer bias (with
// a prior, around b_a, the bias the intervals are corrected with [m/s^2]).
// intervals[k] runs from frames[k] to frames[k+1] and carries the fitted
// gyroscope bias. Returns false with fewer than three frames or a rank-
// deficient system.
bool SolveVelocityGravityScale(const std::vector<AlignmentFrame>& frames,
                               const std::vector<ImuPreintegration>& intervals,
                               const Eigen::Vector3d& t_b_c,
                               const Eigen::Vector3d& b_a,
                               const AlignmentOptions& options,
                               VelocityGravityScale* result);

// The same with |g| held at gravity_magnitude: g = G g_hat + B w, B a basis of
// the plane orthogonal to g_hat, solved for (v_0, w, s, db_a) and iterated
// from result->g_v (VINS-Mono's RefineGravity). result is read and
// overwritten.
bool RefineGravity(const std::vector<AlignmentFrame>& frames,
                   const std::vector<ImuPreintegration>& intervals,
                   const Eigen::Vector3d& t_b_c, const Eigen::Vector3d& b_a,
                   double gravity_magnitude, const AlignmentOptions& options,
                   VelocityGravityScale* result, int iterations = 4);

// The rotation R_w_v that takes g_v onto (0, 0, -|g_v|): the world of
// DESIGN.md (z up) with the yaw of the smallest such rotation.
Eigen::Matrix3d GravityAlignedRotation(const Eigen::Vector3d& g_v);

}  // namespace vio

#endif  // VIO_ESTIMATOR_VISUAL_INERTIAL_ALIGNMENT_H_
