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
// pbar_k (visual units), extrinsic t_b_c; interval k -> k+1 of length T with
// the preintegrated dp, dv, dq (in the body frame at k). Since
// p_v_bk = s pbar_k - R_k t_b_c and the IMU kinematics in v read
//   p_{k+1} = p_k + v_k T + g T^2 / 2 + R_k dp,   v_{k+1} = v_k + g T + R_k dv,
// every interval gives six equations linear in x = (v_0..v_{n-1}, g, s):
//   s (pbar_{k+1} - pbar_k) - T v_k - T^2/2 g = R_k dp + (R_{k+1} - R_k) t_b_c
//   v_{k+1} - v_k - T g                      = R_k dv
// (velocities in v, not in the body frame as VINS-Mono writes them: the same
// system, fewer rotations). The accelerometer bias is taken as given (zero at
// a start); the joint adjustment that follows the alignment estimates it.

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

// The solution of the linear alignment.
struct VelocityGravityScale {
  std::vector<Eigen::Vector3d> v_v;               // per frame, in v [m/s]
  Eigen::Vector3d g_v = Eigen::Vector3d::Zero();  // gravity in v [m/s^2]
  double scale = 1.0;  // metres per visual unit (1 when not estimated)
  // Standard deviation of the scale from the least-squares covariance,
  // sigma^2 (A^T A)^-1 with sigma^2 = |A x - b|^2 / (rows - unknowns) [m/unit];
  // 0 when the scale is not estimated.
  double scale_sigma = 0.0;
  double residual_rms = 0.0;  // of A x - b [m, m/s]
};

// Solves the system above for velocities, gravity (free magnitude) and, with
// estimate_scale, the scale (otherwise s = 1: a metric visual trajectory).
// b_a: the accelerometer bias the intervals are corrected with [m/s^2].
// Returns false when there are fewer than two frames or the system is rank
// deficient.
bool SolveVelocityGravityScale(const std::vector<AlignmentFrame>& frames,
                               const std::vector<ImuPreintegration>& intervals,
                               const Eigen::Vector3d& t_b_c,
                               const Eigen::Vector3d& b_a, bool estimate_scale,
                               VelocityGravityScale* result);

// The same with |g| held at gravity_magnitude: g = G g_hat + B w, B a basis of
// the plane orthogonal to g_hat, solved for (v, w, s) and iterated from
// result->g_v (VINS-Mono's RefineGravity). result is read and overwritten.
bool RefineGravity(const std::vector<AlignmentFrame>& frames,
                   const std::vector<ImuPreintegration>& intervals,
                   const Eigen::Vector3d& t_b_c, const Eigen::Vector3d& b_a,
                   double gravity_magnitude, bool estimate_scale,
                   VelocityGravityScale* result, int iterations = 4);

// The rotation R_w_v that takes g_v onto (0, 0, -|g_v|): the world of
// DESIGN.md (z up) with the yaw of the smallest such rotation.
Eigen::Matrix3d GravityAlignedRotation(const Eigen::Vector3d& g_v);

}  // namespace vio

#endif  // VIO_ESTIMATOR_VISUAL_INERTIAL_ALIGNMENT_H_
