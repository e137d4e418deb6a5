#include "factors/zero_motion_factor.h"

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>

#include "factors/pose_manifold.h"
#include "geometry/so3.h"

namespace vio {

ZeroMotionFactor::ZeroMotionFactor(double sigma_position, double sigma_rotation,
                                   double sigma_velocity) {
  for (double s : {sigma_position, sigma_rotation, sigma_velocity}) {
    if (!(std::isfinite(s) && s > 0.0)) {
      throw std::invalid_argument(
          "ZeroMotionFactor: standard deviations must be finite and > 0");
    }
  }
  inv_sigma_p_ = 1.0 / sigma_position;
  inv_sigma_th_ = 1.0 / sigma_rotation;
  inv_sigma_v_ = 1.0 / sigma_velocity;
}

bool ZeroMotionFactor::Evaluate(double const* const* parameters,
                                double* residuals, double** jacobians) const {
  const double* pose_i = parameters[kPoseI];
  const double* pose_j = parameters[kPoseJ];
  const double* sb_j = parameters[kSpeedBiasJ];
  const Eigen::Map<const Eigen::Vector3d> p_i(pose_i), p_j(pose_j);
  const Eigen::Quaterniond q_i =
      Eigen::Quaterniond(pose_i + kPoseRotation).normalized();
  const Eigen::Quaterniond q_j =
      Eigen::Quaterniond(pose_j + kPoseRotation).normalized();
  const Eigen::Map<const Eigen::Vector3d> v_j(sb_j);
  const Eigen::Quaterniond q_ij = q_i.conjugate() * q_j;
  const Eigen::Vector3d phi = Log(q_ij);
  Eigen::Map<Eigen::Matrix<double, 9, 1>> r(residuals);
  r.segment<3>(kZeroMotionP) = inv_sigma_p_ * (p_j - p_i);
  r.segment<3>(kZeroMotionTheta) = inv_sigma_th_ * phi;
  r.segment<3>(kZeroMotionV) = inv_sigma_v_ * v_j;
  if (!r.allFinite()) return false;
  if (jacobians == nullptr) return true;

  // Rotation: q_j (+) d = q_j Exp(d) gives Log(R_ij Exp(d)) ~ phi + Jr^-1 d;
  // q_i (+) d = q_i Exp(d) gives Exp(-d) R_ij = R_ij Exp(-R_ij^T d), so
  // d phi / d d_i = -Jr^-1 R_ij^T. Positions enter with -I and +I.
  const Eigen::Matrix3d Jr_inv = RightJacobianInverse(phi);
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  if (jacobians[kPoseI] != nullptr) {
    Eigen::Matrix<double, 9, 6> d_r_d_i = Eigen::Matrix<double, 9, 6>::Zero();
    d_r_d_i.block<3, 3>(kZeroMotionP, kPoseTranslation) = -inv_sigma_p_ * I;
    d_r_d_i.block<3, 3>(kZeroMotionTheta, kPoseRotation) =
        -inv_sigma_th_ * Jr_inv * q_ij.toRotationMatrix().transpose();
    LiftPoseJacobian(d_r_d_i, pose_i, jacobians[kPoseI]);
  }
  if (jacobians[kPoseJ] != nullptr) {
    Eigen::Matrix<double, 9, 6> d_r_d_j = Eigen::Matrix<double, 9, 6>::Zero();
    d_r_d_j.block<3, 3>(kZeroMotionP, kPoseTranslation) = inv_sigma_p_ * I;
    d_r_d_j.block<3, 3>(kZeroMotionTheta, kPoseRotation) =
        inv_sigma_th_ * Jr_inv;
    LiftPoseJacobian(d_r_d_j, pose_j, jacobians[kPoseJ]);
  }
  if (jacobians[kSpeedBiasJ] != nullptr) {
    // Only v_j: the biases are not constrained by standing still.
    Eigen::Map<Eigen::Matrix<double, 9, 9, Eigen::RowMajor>> d_r_d_sb(
        jacobians[kSpeedBiasJ]);
    d_r_d_sb.setZero();
    d_r_d_sb.block<3, 3>(kZeroMotionV, 0) = inv_sigma_v_ * I;
  }
  return true;
}

}  // namespace vio
