#ifndef VIO_FACTORS_ZERO_MOTION_FACTOR_H_
#define VIO_FACTORS_ZERO_MOTION_FACTOR_H_

// The zero-motion (zero-velocity) constraint between two window frames i and
// j between which the vehicle stood still (estimator/zero_velocity.h): the
// pose did not change and the velocity at j is zero.
//
//   r_p  = (p_j - p_i) / sigma_p                        (3)
//   r_th = Log(q_i^-1 (x) q_j) / sigma_th               (3)
//   r_v  = v_j / sigma_v                                (3)
//
// Parameter blocks, in this order (DESIGN.md layouts):
//   pose_i (7)        [p_w_bi, q_w_bi (x, y, z, w)]   manifold: PoseManifold
//   pose_j (7)        [p_w_bj, q_w_bj]                manifold: PoseManifold
//   speed_bias_j (9)  [v_w_j, b_a_j, b_g_j]           Euclidean
// Jacobians are derived in the tangent space of the project's right
// perturbation (q (+) d = q (x) Exp(d), p (+) d = p + d; the .cc) and lifted
// to the 7-wide pose blocks with LiftPoseJacobian (pose_manifold.h).
//
// Why a factor of its own rather than a prior: it ties consecutive frames to
// each other, not to a fixed value, so a still vehicle keeps whatever pose
// the window holds while the IMU's drift (bias errors integrated over a long
// still interval) is held off. OpenVINS applies a zero-velocity update with
// the IMU's expected readings; at rest in a sliding window this relative form
// also stops the yaw drift of the gyroscope bias.

#include <ceres/sized_cost_function.h>

namespace vio {

// Slots of the residual.
constexpr int kZeroMotionP = 0;
constexpr int kZeroMotionTheta = 3;
constexpr int kZeroMotionV = 6;

class ZeroMotionFactor final : public ceres::SizedCostFunction<9, 7, 7, 9> {
 public:
  enum Block { kPoseI = 0, kPoseJ = 1, kSpeedBiasJ = 2 };

  // Standard deviations of the position [m], attitude [rad] and velocity
  // [m/s] constraints; each > 0 (std::invalid_argument otherwise).
  ZeroMotionFactor(double sigma_position, double sigma_rotation,
                   double sigma_velocity);

  // Never throws; returns false when an input or the result is not finite.
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  double inv_sigma_p_;
  double inv_sigma_th_;
  double inv_sigma_v_;
};

}  // namespace vio

#endif  // VIO_FACTORS_ZERO_MOTION_FACTOR_H_
