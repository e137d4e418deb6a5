#include "factors/timed_reprojection_factor.h"

#include "factors/inverse_depth_chain.h"

namespace vio {
namespace {

// xy(t_d) = xy - (t_d - t_d_at_stamp) * velocity.
Eigen::Vector2d Shifted(const TimedObservation& obs, double t_d) {
  return obs.xy - (t_d - obs.t_d_at_stamp) * obs.velocity;
}

// t_d moves both observations: d f_i / d t_d = (-v_i, 0) through the chain,
// and d xy_j(t_d) / d t_d = -v_j enters r = sqrt_info (pi(h_c) - xy_j) with a
// minus sign:
//   d r / d t_d = -d_r_d_h (d h_c / d f_i)[:, 0:2] v_i + sqrt_info v_j.
// Zero, as every Jacobian of the factor, when the residual is inactive
// (ProjectResidual: the point behind or at the centre of the camera).
void WriteTimeOffsetJacobian(const ProjectedResidual& p,
                             const InverseDepthChain& chain,
                             const TimedObservation& obs_i,
                             const TimedObservation& obs_j, double sqrt_info,
                             double* jacobian) {
  if (jacobian == nullptr) return;
  Eigen::Map<Eigen::Vector2d> d_r_d_td(jacobian);
  d_r_d_td.setZero();
  if (p.active) {
    d_r_d_td =
        -p.d_r_d_h * chain.d_h_d_bearing().leftCols<2>() * obs_i.velocity +
        sqrt_info * obs_j.velocity;
  }
}

}  // namespace

TimedReprojectionFactor::TimedReprojectionFactor(const TimedObservation& obs_i,
                                                 const TimedObservation& obs_j,
                                                 double sqrt_info)
    : obs_i_(obs_i), obs_j_(obs_j), sqrt_info_(sqrt_info) {}

bool TimedReprojectionFactor::Evaluate(double const* const* parameters,
                                       double* residuals,
                                       double** jacobians) const {
  return Compute(parameters, residuals, jacobians, /*tangent=*/false);
}

bool TimedReprojectionFactor::EvaluateTangent(double const* const* parameters,
                                              double* residuals,
                                              double** jacobians) const {
  return Compute(parameters, residuals, jacobians, /*tangent=*/true);
}

bool TimedReprojectionFactor::Compute(double const* const* parameters,
                                      double* residuals, double** jacobians,
                                      bool tangent) const {
  const double t_d = parameters[kTimeOffset][0];
  const Eigen::Vector2d xy_i = Shifted(obs_i_, t_d);
  const Eigen::Vector3d f_i(xy_i.x(), xy_i.y(), 1.0);
  const Rigid T_b_c = Rigid::FromBlock(parameters[kExtrinsic]);
  const InverseDepthChain chain(f_i, parameters[kInverseDepth][0], T_b_c,
                                Rigid::FromBlock(parameters[kPoseI]),
                                Rigid::FromBlock(parameters[kPoseJ]), T_b_c);
  const ProjectedResidual p =
      ProjectResidual(chain.h_c(), Shifted(obs_j_, t_d), sqrt_info_);
  Eigen::Map<Eigen::Vector2d> r(residuals);
  r = p.r;
  if (jacobians == nullptr) return true;

  // Poses, extrinsic and rho: as in ReprojectionFactor, on the shifted f_i.
  WriteChainJacobians(
      p, chain,
      {ChainBlock::kPoseI, ChainBlock::kPoseJ, ChainBlock::kSharedExtrinsic,
       ChainBlock::kInverseDepth},
      parameters, jacobians,
      tangent ? JacobianSpace::kTangent : JacobianSpace::kAmbient);
  WriteTimeOffsetJacobian(p, chain, obs_i_, obs_j_, sqrt_info_,
                          jacobians[kTimeOffset]);
  return true;
}

TimedStereoTwoFrameReprojectionFactor::TimedStereoTwoFrameReprojectionFactor(
    const TimedObservation& obs_i, const TimedObservation& obs_j,
    double sqrt_info)
    : obs_i_(obs_i), obs_j_(obs_j), sqrt_info_(sqrt_info) {}

bool TimedStereoTwoFrameReprojectionFactor::Evaluate(
    double const* const* parameters, double* residuals,
    double** jacobians) const {
  return Compute(parameters, residuals, jacobians, /*tangent=*/false);
}

bool TimedStereoTwoFrameReprojectionFactor::EvaluateTangent(
    double const* const* parameters, double* residuals,
    double** jacobians) const {
  return Compute(parameters, residuals, jacobians, /*tangent=*/true);
}

bool TimedStereoTwoFrameReprojectionFactor::Compute(
    double const* const* parameters, double* residuals, double** jacobians,
    bool tangent) const {
  const double t_d = parameters[kTimeOffset][0];
  const Eigen::Vector2d xy_i = Shifted(obs_i_, t_d);
  const Eigen::Vector3d f_i(xy_i.x(), xy_i.y(), 1.0);
  const InverseDepthChain chain(f_i, parameters[kInverseDepth][0],
                                Rigid::FromBlock(parameters[kExtrinsic0]),
                                Rigid::FromBlock(parameters[kPoseI]),
                                Rigid::FromBlock(parameters[kPoseJ]),
                                Rigid::FromBlock(parameters[kExtrinsic1]));
  const ProjectedResidual p =
      ProjectResidual(chain.h_c(), Shifted(obs_j_, t_d), sqrt_info_);
  Eigen::Map<Eigen::Vector2d> r(residuals);
  r = p.r;
  if (jacobians == nullptr) return true;

  // Poses, extrinsics and rho: as in StereoTwoFrameReprojectionFactor, on
  // the shifted f_i.
  WriteChainJacobians(
      p, chain,
      {ChainBlock::kPoseI, ChainBlock::kPoseJ, ChainBlock::kAnchorExtrinsic,
       ChainBlock::kTargetExtrinsic, ChainBlock::kInverseDepth},
      parameters, jacobians,
      tangent ? JacobianSpace::kTangent : JacobianSpace::kAmbient);
  WriteTimeOffsetJacobian(p, chain, obs_i_, obs_j_, sqrt_info_,
                          jacobians[kTimeOffset]);
  return true;
}

}  // namespace vio
