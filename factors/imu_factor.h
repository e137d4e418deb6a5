#ifndef VIO_FACTORS_IMU_FACTOR_H_
#define VIO_FACTORS_IMU_FACTOR_H_

// The IMU factor between keyframes i and j: the preintegrated motion of the
// interval [t_i, t_j] against the states at its ends.
//
// Parameter blocks (DESIGN.md layouts), in this order:
//   pose_i (7)        [p_w_bi, q_w_bi (x, y, z, w)]   manifold: PoseManifold
//   speed_bias_i (9)  [v_w_i, b_a_i, b_g_i]           Euclidean
//   pose_j (7)        [p_w_bj, q_w_bj]                manifold: PoseManifold
//   speed_bias_j (9)  [v_w_j, b_a_j, b_g_j]           Euclidean
// Residual (15, DESIGN.md order), with T = t_j - t_i, g_w = (0, 0, -g) and the
// first-order bias-corrected preintegration dp, dq, dv at b_a_i, b_g_i
// (PreintegratedImu::Corrected):
//   r_p  = R_i^T (p_j - p_i - v_i T - g_w T^2 / 2) - dp
//   r_th = Log(dq^-1 (x) q_i^-1 (x) q_j)
//   r_v  = R_i^T (v_j - v_i - g_w T) - dv
//   r_ba = b_a_j - b_a_i
//   r_bg = b_g_j - b_g_i
// weighted as U r with U = LLT(P^-1).matrixL()^T, P the preintegrated
// covariance, so that |U r|^2 = r^T P^-1 r.
//
// Jacobians are derived in the tangent space under the project's right
// perturbation (q (+) d = q (x) Exp(d), p (+) d = p + d; imu_factor.cc) and
// lifted to the 7-wide pose blocks with LiftPoseJacobian (pose_manifold.h).
//
// References: Forster et al., "On-Manifold Preintegration for Real-Time
// Visual-Inertial Odometry", T-RO 2017, sec. V-C (bias update) and V-D
// (residuals); Qin et al., "VINS-Mono", T-RO 2018, sec. IV-B (midpoint
// preintegration) and VI-B (IMU measurement residual).

#include <ceres/sized_cost_function.h>

#include <Eigen/Core>

#include "preintegration/imu_preintegration.h"

namespace vio {

// Parameter block indices.
constexpr int kImuFactorPoseI = 0;
constexpr int kImuFactorSpeedBiasI = 1;
constexpr int kImuFactorPoseJ = 2;
constexpr int kImuFactorSpeedBiasJ = 3;

// Slots of the speed-bias block.
constexpr int kSpeedBiasV = 0;
constexpr int kSpeedBiasBa = 3;
constexpr int kSpeedBiasBg = 6;
constexpr int kSpeedBiasSize = 9;

class ImuFactor final : public ceres::SizedCostFunction<15, 7, 9, 7, 9> {
 public:
  // Copies what it needs from the preintegration (rebuild the factor after
  // re-propagating). gravity_magnitude [m/s^2] > 0. Throws
  // std::invalid_argument when the covariance is not positive definite.
  ImuFactor(const PreintegratedImu& preintegrated, double gravity_magnitude);

  // Never throws; returns false when an input, the residual or a Jacobian is
  // not finite.
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

  // The residual before weighting (for diagnostics and tests); false when it
  // is not finite.
  bool UnweightedResidual(double const* const* parameters,
                          Vector15d* residual) const;

  const Matrix15d& sqrt_information() const { return sqrt_information_; }
  const PreintegratedImu& preintegrated() const { return preintegrated_; }

 private:
  struct Terms;

  bool ComputeTerms(double const* const* parameters, Terms* terms) const;
  void PoseIJacobian(const Terms& t, const double* pose_i,
                     double* jacobian) const;
  void SpeedBiasIJacobian(const Terms& t, double* jacobian) const;
  void PoseJJacobian(const Terms& t, const double* pose_j,
                     double* jacobian) const;
  void SpeedBiasJJacobian(const Terms& t, double* jacobian) const;

  PreintegratedImu preintegrated_;
  Eigen::Vector3d g_w_;
  Matrix15d sqrt_information_;
};

}  // namespace vio

#endif  // VIO_FACTORS_IMU_FACTOR_H_
