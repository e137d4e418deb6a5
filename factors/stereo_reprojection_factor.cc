#include "factors/stereo_reprojection_factor.h"

#include "factors/inverse_depth_chain.h"

namespace vio {

StereoReprojectionFactor::StereoReprojectionFactor(const Eigen::Vector2d& xy_c0,
                                                   const Eigen::Vector2d& xy_c1,
                                                   double sqrt_info)
    : f_i_(xy_c0.x(), xy_c0.y(), 1.0), xy_c1_(xy_c1), sqrt_info_(sqrt_info) {}

bool StereoReprojectionFactor::Evaluate(double const* const* parameters,
                                        double* residuals,
                                        double** jacobians) const {
  return Compute(parameters, residuals, jacobians, /*tangent=*/false);
}

bool StereoReprojectionFactor::EvaluateTangent(double const* const* parameters,
                                               double* residuals,
                                               double** jacobians) const {
  return Compute(parameters, residuals, jacobians, /*tangent=*/true);
}

bool StereoReprojectionFactor::Compute(double const* const* parameters,
                                       double* residuals, double** jacobians,
                                       bool tangent) const {
  // One keyframe: the body pose cancels, h_c1 = R_b_c1^T (R_b_c0 f +
  // rho (t_b_c0 - t_b_c1)).
  const InverseDepthChain chain(f_i_, parameters[kInverseDepth][0],
                                Rigid::FromBlock(parameters[kExtrinsic0]),
                                Rigid::FromBlock(parameters[kExtrinsic1]));
  const ProjectedResidual p = ProjectResidual(chain.h_c(), xy_c1_, sqrt_info_);
  Eigen::Map<Eigen::Vector2d> r(residuals);
  r = p.r;
  if (jacobians != nullptr) {
    // cam0 is the anchor and cam1 the target of the shared chain.
    WriteChainJacobians(
        p, chain,
        {ChainBlock::kAnchorExtrinsic, ChainBlock::kTargetExtrinsic,
         ChainBlock::kInverseDepth},
        parameters, jacobians,
        tangent ? JacobianSpace::kTangent : JacobianSpace::kAmbient);
  }
  return true;
}

StereoTwoFrameReprojectionFactor::StereoTwoFrameReprojectionFactor(
    const Eigen::Vector2d& xy_i, const Eigen::Vector2d& xy_j, double sqrt_info)
    : f_i_(xy_i.x(), xy_i.y(), 1.0), xy_j_(xy_j), sqrt_info_(sqrt_info) {}

bool StereoTwoFrameReprojectionFactor::Evaluate(double const* const* parameters,
                                                double* residuals,
                                                double** jacobians) const {
  return Compute(parameters, residuals, jacobians, /*tangent=*/false);
}

bool StereoTwoFrameReprojectionFactor::EvaluateTangent(
    double const* const* parameters, double* residuals,
    double** jacobians) const {
  return Compute(parameters, residuals, jacobians, /*tangent=*/true);
}

bool StereoTwoFrameReprojectionFactor::Compute(double const* const* parameters,
                                               double* residuals,
                                               double** jacobians,
                                               bool tangent) const {
  Eigen::Map<Eigen::Vector2d> r(residuals);
  if (jacobians == nullptr) {
    r = ProjectResidual(InverseDepthChain::PointInTarget(
                            f_i_, parameters[kInverseDepth][0],
                            Rigid::FromBlock(parameters[kExtrinsic0]),
                            Rigid::FromBlock(parameters[kPoseI]),
                            Rigid::FromBlock(parameters[kPoseJ]),
                            Rigid::FromBlock(parameters[kExtrinsic1])),
                        xy_j_, sqrt_info_)
            .r;
    return true;
  }
  const InverseDepthChain chain(f_i_, parameters[kInverseDepth][0],
                                Rigid::FromBlock(parameters[kExtrinsic0]),
                                Rigid::FromBlock(parameters[kPoseI]),
                                Rigid::FromBlock(parameters[kPoseJ]),
                                Rigid::FromBlock(parameters[kExtrinsic1]));
  const ProjectedResidual p = ProjectResidual(chain.h_c(), xy_j_, sqrt_info_);
  r = p.r;
  // cam0 of keyframe i is the anchor, cam1 of keyframe j the target.
  WriteChainJacobians(
      p, chain,
      {ChainBlock::kPoseI, ChainBlock::kPoseJ, ChainBlock::kAnchorExtrinsic,
       ChainBlock::kTargetExtrinsic, ChainBlock::kInverseDepth},
      parameters, jacobians,
      tangent ? JacobianSpace::kTangent : JacobianSpace::kAmbient);
  return true;
}

}  // namespace vio
