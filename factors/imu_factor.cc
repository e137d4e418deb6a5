#include "factors/imu_factor.h"

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>

#include "factors/pose_manifold.h"
#include "geometry/so3.h"

namespace vio {
namespace {

using Matrix15x6 = Eigen::Matrix<double, 15, 6>;
using Matrix15x9 = Eigen::Matrix<double, 15, 9>;

template <int kSize>
bool AllFinite(const double* x) {
  return Eigen::Map<const Eigen::Matrix<double, kSize, 1>>(x).allFinite();
}

}  // namespace

// Everything the residual and the four Jacobian blocks share.
struct ImuFactor::Terms {
  Eigen::Matrix3d R_i_T;      // R_w_bi^T
  Eigen::Matrix3d R_j;        // R_w_bj
  Eigen::Vector3d dp_w;       // p_j - p_i - v_i T - g_w T^2 / 2, in W
  Eigen::Vector3d dv_w;       // v_j - v_i - g_w T, in W
  Eigen::Matrix3d Jr_inv_th;  // Jr^-1(r_th)
  Eigen::Matrix3d R_err_T;    // Exp(r_th)^T
  Eigen::Matrix3d Jr_corr;    // Jr(d_dq_d_bg (b_g_i - lin_b_g))
  Vector15d r;                // unweighted residual
};

ImuFactor::ImuFactor(const PreintegratedImu& preintegrated,
                     double gravity_magnitude)
    : preintegrated_(preintegrated), g_w_(0.0, 0.0, -gravity_magnitude) {
  if (!(gravity_magnitude > 0.0) || !std::isfinite(gravity_magnitude)) {
    throw std::invalid_argument("ImuFactor: gravity_magnitude must be > 0");
  }
  const Eigen::LLT<Matrix15d> llt_cov(preintegrated.covariance);
  if (llt_cov.info() != Eigen::Success) {
    throw std::invalid_argument(
        "ImuFactor: the preintegrated covariance is not positive definite");
  }
  const Matrix15d information = llt_cov.solve(Matrix15d::Identity());
  const Eigen::LLT<Matrix15d> llt_info(0.5 *
                                       (information + information.transpose()));
  if (llt_info.info() != Eigen::Success) {
    throw std::invalid_argument(
        "ImuFactor: the preintegrated information is not positive definite");
  }
  sqrt_information_ = llt_info.matrixL().transpose();
}

bool ImuFactor::ComputeTerms(double const* const* parameters, Terms* t) const {
  if (!AllFinite<7>(parameters[kImuFactorPoseI]) ||
      !AllFinite<9>(parameters[kImuFactorSpeedBiasI]) ||
      !AllFinite<7>(parameters[kImuFactorPoseJ]) ||
      !AllFinite<9>(parameters[kImuFactorSpeedBiasJ])) {
    return false;
  }
  const Eigen::Map<const Eigen::Vector3d> p_i(parameters[kImuFactorPoseI]);
  const Eigen::Map<const Eigen::Quaterniond> q_i(parameters[kImuFactorPoseI] +
                                                 3);
  const Eigen::Map<const Eigen::Vector3d> p_j(parameters[kImuFactorPoseJ]);
  const Eigen::Map<const Eigen::Quaterniond> q_j(parameters[kImuFactorPoseJ] +
                                                 3);
  const double* sb_i = parameters[kImuFactorSpeedBiasI];
  const double* sb_j = parameters[kImuFactorSpeedBiasJ];
  const Eigen::Map<const Eigen::Vector3d> v_i(sb_i + kSpeedBiasV);
  const Eigen::Map<const Eigen::Vector3d> b_a_i(sb_i + kSpeedBiasBa);
  const Eigen::Map<const Eigen::Vector3d> b_g_i(sb_i + kSpeedBiasBg);
  const Eigen::Map<const Eigen::Vector3d> v_j(sb_j + kSpeedBiasV);
  const Eigen::Map<const Eigen::Vector3d> b_a_j(sb_j + kSpeedBiasBa);
  const Eigen::Map<const Eigen::Vector3d> b_g_j(sb_j + kSpeedBiasBg);

  const PreintegratedImu& pre = preintegrated_;
  const double T = pre.sum_dt;
  const ImuDelta corrected = pre.Corrected(b_a_i, b_g_i);

  t->R_i_T = q_i.toRotationMatrix().transpose();
  t->R_j = q_j.toRotationMatrix();
  t->dp_w = p_j - p_i - v_i * T - 0.5 * g_w_ * T * T;
  t->dv_w = v_j - v_i - g_w_ * T;
  const Eigen::Quaterniond q_err =
      corrected.q.conjugate() * q_i.conjugate() * q_j;
  const Eigen::Vector3d r_th = Log(q_err);
  t->Jr_inv_th = RightJacobianInverse(r_th);
  t->R_err_T = q_err.toRotationMatrix().transpose();
  t->Jr_corr = RightJacobian(pre.d_dq_d_bg * (b_g_i - pre.lin_b_g));

  t->r.segment<3>(kImuP) = t->R_i_T * t->dp_w - corrected.p;
  t->r.segment<3>(kImuR) = r_th;
  t->r.segment<3>(kImuV) = t->R_i_T * t->dv_w - corrected.v;
  t->r.segment<3>(kImuBa) = b_a_j - b_a_i;
  t->r.segment<3>(kImuBg) = b_g_j - b_g_i;
  return t->r.allFinite();
}

bool ImuFactor::UnweightedResidual(double const* const* parameters,
                                   Vector15d* residual) const {
  Terms t;
  if (!ComputeTerms(parameters, &t)) return false;
  *residual = t.r;
  return true;
}

void ImuFactor::PoseIJacobian(const Terms& t, const double* pose_i,
                              double* jacobian) const {
  Matrix15x6 J = Matrix15x6::Zero();
  // r_p = R_i^T dp_w - dp. p_i + e: dp_w - e. R_i Exp(d): R_i^T -> Exp(-d)
  // R_i^T ~ (I - [d]x) R_i^T, so d (R_i^T x) / d d = [R_i^T x]x.
  J.block<3, 3>(kImuP, kPoseTranslation) = -t.R_i_T;
  J.block<3, 3>(kImuP, kPoseRotation) = Skew(t.R_i_T * t.dp_w);
  // r_th = Log(E), E = dq^-1 q_i^-1 q_j. q_i Exp(d) gives
  // dq^-1 Exp(-d) q_i^-1 q_j = Exp(-R_dq^T d) E = E Exp(-R_E^T R_dq^T d), and
  // R_dq R_E = R_i^T R_j, so d r_th / d d = -Jr^-1(r_th) R_j^T R_i.
  J.block<3, 3>(kImuR, kPoseRotation) =
      -t.Jr_inv_th * t.R_j.transpose() * t.R_i_T.transpose();
  // r_v = R_i^T dv_w - dv: same rotation derivative as r_p.
  J.block<3, 3>(kImuV, kPoseRotation) = Skew(t.R_i_T * t.dv_w);
  LiftPoseJacobian(Matrix15x6(sqrt_information_ * J), pose_i, jacobian);
}

void ImuFactor::SpeedBiasIJacobian(const Terms& t, double* jacobian) const {
  const PreintegratedImu& pre = preintegrated_;
  Matrix15x9 J = Matrix15x9::Zero();
  // r_p, r_v are linear in v_i and, through the first-order correction, in
  // the biases: d dp / d b = d_dp_d_b, d dv / d b = d_dv_d_b.
  J.block<3, 3>(kImuP, kSpeedBiasV) = -t.R_i_T * pre.sum_dt;
  J.block<3, 3>(kImuP, kSpeedBiasBa) = -pre.d_dp_d_ba;
  J.block<3, 3>(kImuP, kSpeedBiasBg) = -pre.d_dp_d_bg;
  J.block<3, 3>(kImuV, kSpeedBiasV) = -t.R_i_T;
  J.block<3, 3>(kImuV, kSpeedBiasBa) = -pre.d_dv_d_ba;
  J.block<3, 3>(kImuV, kSpeedBiasBg) = -pre.d_dv_d_bg;
  // dq = dq0 Exp(phi), phi = J_q (b_g_i - lin_b_g). b_g_i + e:
  // Exp(phi + J_q e) ~ Exp(phi) Exp(Jr(phi) J_q e) =: dq Exp(x), so
  // E -> Exp(-x) E = E Exp(-R_E^T x) and
  // d r_th / d b_g_i = -Jr^-1(r_th) R_E^T Jr(phi) J_q.
  J.block<3, 3>(kImuR, kSpeedBiasBg) =
      -t.Jr_inv_th * t.R_err_T * t.Jr_corr * pre.d_dq_d_bg;
  J.block<3, 3>(kImuBa, kSpeedBiasBa) = -Eigen::Matrix3d::Identity();
  J.block<3, 3>(kImuBg, kSpeedBiasBg) = -Eigen::Matrix3d::Identity();
  Eigen::Map<Eigen::Matrix<double, 15, 9, Eigen::RowMajor>> out(jacobian);
  out = sqrt_information_ * J;
}

void ImuFactor::PoseJJacobian(const Terms& t, const double* pose_j,
                              double* jacobian) const {
  Matrix15x6 J = Matrix15x6::Zero();
  // p_j + e moves r_p by R_i^T e. q_j Exp(d) gives E Exp(d), so
  // d r_th / d d = Jr^-1(r_th).
  J.block<3, 3>(kImuP, kPoseTranslation) = t.R_i_T;
  J.block<3, 3>(kImuR, kPoseRotation) = t.Jr_inv_th;
  LiftPoseJacobian(Matrix15x6(sqrt_information_ * J), pose_j, jacobian);
}

void ImuFactor::SpeedBiasJJacobian(const Terms& t, double* jacobian) const {
  Matrix15x9 J = Matrix15x9::Zero();
  // Linear: r_v gains R_i^T e for v_j + e; the bias residuals gain e.
  J.block<3, 3>(kImuV, kSpeedBiasV) = t.R_i_T;
  J.block<3, 3>(kImuBa, kSpeedBiasBa).setIdentity();
  J.block<3, 3>(kImuBg, kSpeedBiasBg).setIdentity();
  Eigen::Map<Eigen::Matrix<double, 15, 9, Eigen::RowMajor>> out(jacobian);
  out = sqrt_information_ * J;
}

bool ImuFactor::Evaluate(double const* const* parameters, double* residuals,
                         double** jacobians) const {
  Terms t;
  if (!ComputeTerms(parameters, &t)) return false;
  Eigen::Map<Vector15d> weighted(residuals);
  weighted = sqrt_information_ * t.r;
  if (!weighted.allFinite()) return false;
  if (jacobians == nullptr) return true;
  if (jacobians[kImuFactorPoseI] != nullptr) {
    PoseIJacobian(t, parameters[kImuFactorPoseI], jacobians[kImuFactorPoseI]);
    if (!AllFinite<15 * 7>(jacobians[kImuFactorPoseI])) return false;
  }
  if (jacobians[kImuFactorSpeedBiasI] != nullptr) {
    SpeedBiasIJacobian(t, jacobians[kImuFactorSpeedBiasI]);
    if (!AllFinite<15 * 9>(jacobians[kImuFactorSpeedBiasI])) return false;
  }
  if (jacobians[kImuFactorPoseJ] != nullptr) {
    PoseJJacobian(t, parameters[kImuFactorPoseJ], jacobians[kImuFactorPoseJ]);
    if (!AllFinite<15 * 7>(jacobians[kImuFactorPoseJ])) return false;
  }
  if (jacobians[kImuFactorSpeedBiasJ] != nullptr) {
    SpeedBiasJJacobian(t, jacobians[kImuFactorSpeedBiasJ]);
    if (!AllFinite<15 * 9>(jacobians[kImuFactorSpeedBiasJ])) return false;
  }
  return true;
}

}  // namespace vio
