#include "factors/world_point_factor.h"

#include "factors/inverse_depth_chain.h"
#include "factors/pose_manifold.h"
#include "geometry/so3.h"

namespace vio {
namespace {

// Writes a 2 x 6 tangent Jacobian as it is or lifted to the ambient 2 x 7.
void WriteRigid(const Matrix26& d_r_d_tangent, const double* x, bool tangent,
                double* jacobian) {
  if (tangent) {
    Eigen::Map<Eigen::Matrix<double, 2, 6, Eigen::RowMajor>> out(jacobian);
    out = d_r_d_tangent;
  } else {
    LiftPoseJacobian(d_r_d_tangent, x, jacobian);
  }
}

}  // namespace

WorldPointReprojectionFactor::WorldPointReprojectionFactor(
    const Eigen::Vector2d& xy, double sqrt_info, const double* p_w_first)
    : xy_(xy), sqrt_info_(sqrt_info), p_w_first_(p_w_first) {}

bool WorldPointReprojectionFactor::Evaluate(double const* const* parameters,
                                            double* residuals,
                                            double** jacobians) const {
  WorldPointReprojection(parameters, xy_, sqrt_info_, p_w_first_,
                         /*tangent=*/false, residuals, jacobians);
  return true;
}

bool WorldPointReprojectionFactor::EvaluateTangent(
    double const* const* parameters, double* residuals,
    double** jacobians) const {
  WorldPointReprojection(parameters, xy_, sqrt_info_, p_w_first_,
                         /*tangent=*/true, residuals, jacobians);
  return true;
}

bool WorldPointReprojection(double const* const* parameters,
                            const Eigen::Vector2d& xy, double sqrt_info,
                            const double* p_w_first, bool tangent,
                            double* residuals, double** jacobians) {
  constexpr int kPose = WorldPointReprojectionFactor::kPose;
  constexpr int kExtrinsic = WorldPointReprojectionFactor::kExtrinsic;
  constexpr int kPoint = WorldPointReprojectionFactor::kPoint;
  const Rigid T_w_b = Rigid::FromBlock(parameters[kPose]);
  const Rigid T_b_c = Rigid::FromBlock(parameters[kExtrinsic]);
  const Eigen::Map<const Eigen::Vector3d> p_w(parameters[kPoint]);
  Eigen::Vector3d p_b = T_w_b.R.transpose() * (p_w - T_w_b.t);
  Eigen::Vector3d p_c = T_b_c.R.transpose() * (p_b - T_b_c.t);
  ProjectedResidual p = ProjectResidual(p_c, xy, sqrt_info);
  Eigen::Map<Eigen::Vector2d> r(residuals);
  r = p.r;
  if (jacobians == nullptr) return p.active;
  if (p_w_first != nullptr) {
    // The same chain at the first estimate, for the Jacobians only.
    const Eigen::Map<const Eigen::Vector3d> p_first(p_w_first);
    p_b = T_w_b.R.transpose() * (p_first - T_w_b.t);
    p_c = T_b_c.R.transpose() * (p_b - T_b_c.t);
    p = ProjectResidual(p_c, xy, sqrt_info);
  }
  // d_r_d_h is zero when inactive, so every Jacobian below is then zero.
  const Matrix23 d_r_d_pb = p.d_r_d_h * T_b_c.R.transpose();
  if (jacobians[kPose] != nullptr) {
    Matrix26 d;
    d.leftCols<3>() = -d_r_d_pb * T_w_b.R.transpose();
    d.rightCols<3>() = d_r_d_pb * Skew(p_b);
    WriteRigid(d, parameters[kPose], tangent, jacobians[kPose]);
  }
  if (jacobians[kExtrinsic] != nullptr) {
    Matrix26 d;
    d.leftCols<3>() = -d_r_d_pb;
    d.rightCols<3>() = p.d_r_d_h * Skew(p_c);
    WriteRigid(d, parameters[kExtrinsic], tangent, jacobians[kExtrinsic]);
  }
  if (jacobians[kPoint] != nullptr) {
    Eigen::Map<Eigen::Matrix<double, 2, 3, Eigen::RowMajor>> d_r_d_p(
        jacobians[kPoint]);
    d_r_d_p = d_r_d_pb * T_w_b.R.transpose();
  }
  return p.active;
}

}  // namespace vio
