#include "factors/reprojection_factor.h"

#include "factors/inverse_depth_chain.h"

namespace vio {

ReprojectionFactor::ReprojectionFactor(const Eigen::Vector2d& xy_i,
                                       const Eigen::Vector2d& xy_j,
                                       double sqrt_info)
    : f_i_(xy_i.x(), xy_i.y(), 1.0), xy_j_(xy_j), sqrt_info_(sqrt_info) {}

bool ReprojectionFactor::Evaluate(double const* const* parameters,
                                  double* residuals, double** jacobians) const {
  const Rigid T_b_c = Rigid::FromBlock(parameters[kExtrinsic]);
  const double rho = parameters[kInverseDepth][0];
  const InverseDepthChain chain(f_i_, rho, T_b_c,
                                Rigid::FromBlock(parameters[kPoseI]),
                                Rigid::FromBlock(parameters[kPoseJ]), T_b_c);
  const ProjectedResidual p = ProjectResidual(chain.h_c(), xy_j_, sqrt_info_);
  Eigen::Map<Eigen::Vector2d> r(residuals);
  r = p.r;
  if (jacobians == nullptr) return true;

  // r = pi(h_c) and h_c depends on each block through the shared chain:
  // d r / d block = d_r_d_h * d_h_d_block.
  if (jacobians[kPoseI] != nullptr) {
    WriteRigidJacobian(p, chain.d_h_d_pose_i(), parameters[kPoseI],
                       jacobians[kPoseI]);
  }
  if (jacobians[kPoseJ] != nullptr) {
    WriteRigidJacobian(p, chain.d_h_d_pose_j(), parameters[kPoseJ],
                       jacobians[kPoseJ]);
  }
  if (jacobians[kExtrinsic] != nullptr) {
    // One camera is both the anchor and the target: T_b_c enters the chain
    // twice, and its Jacobian is the sum of both paths.
    WriteRigidJacobian(
        p, chain.d_h_d_anchor_extrinsic() + chain.d_h_d_target_extrinsic(),
        parameters[kExtrinsic], jacobians[kExtrinsic]);
  }
  if (jacobians[kInverseDepth] != nullptr) {
    Eigen::Map<Eigen::Vector2d> d_r_d_rho(jacobians[kInverseDepth]);
    d_r_d_rho = p.d_r_d_h * chain.d_h_d_rho();
  }
  return true;
}

}  // namespace vio
