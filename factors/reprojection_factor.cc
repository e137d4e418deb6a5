#include "factors/reprojection_factor.h"

#include "factors/inverse_depth_chain.h"

namespace vio {

ReprojectionFactor::ReprojectionFactor(const Eigen::Vector2d& xy_i,
                                       const Eigen::Vector2d& xy_j,
                                       double sqrt_info)
    : f_i_(xy_i.x(), xy_i.y(), 1.0), xy_j_(xy_j), sqrt_info_(sqrt_info) {}

bool ReprojectionFactor::Evaluate(double const* const* parameters,
                                  double* residuals, double** jacobians) const {
  return Compute(parameters, residuals, jacobians, /*tangent=*/false);
}

bool ReprojectionFactor::EvaluateTangent(double const* const* parameters,
                                         double* residuals,
                                         double** jacobians) const {
  return Compute(parameters, residuals, jacobians, /*tangent=*/true);
}

bool ReprojectionFactor::Compute(double const* const* parameters,
                                 double* residuals, double** jacobians,
                                 bool tangent) const {
  const Rigid T_b_c = Rigid::FromBlock(parameters[kExtrinsic]);
  const double rho = parameters[kInverseDepth][0];
  Eigen::Map<Eigen::Vector2d> r(residuals);
  if (jacobians == nullptr) {
    r = ProjectResidual(
            InverseDepthChain::PointInTarget(
                f_i_, rho, T_b_c, Rigid::FromBlock(parameters[kPoseI]),
                Rigid::FromBlock(parameters[kPoseJ]), T_b_c),
            xy_j_, sqrt_info_)
            .r;
    return true;
  }
  const InverseDepthChain chain(f_i_, rho, T_b_c,
                                Rigid::FromBlock(parameters[kPoseI]),
                                Rigid::FromBlock(parameters[kPoseJ]), T_b_c);
  const ProjectedResidual p = ProjectResidual(chain.h_c(), xy_j_, sqrt_info_);
  r = p.r;
  // One camera is both the anchor and the target: T_b_c enters the chain
  // twice (kSharedExtrinsic sums both paths).
  WriteChainJacobians(
      p, chain,
      {ChainBlock::kPoseI, ChainBlock::kPoseJ, ChainBlock::kSharedExtrinsic,
       ChainBlock::kInverseDepth},
      parameters, jacobians,
      tangent ? JacobianSpace::kTangent : JacobianSpace::kAmbient);
  return true;
}

}  // namespace vio
