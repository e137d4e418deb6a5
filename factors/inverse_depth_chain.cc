#include "factors/inverse_depth_chain.h"

#include <Eigen/Geometry>

#include "factors/pose_manifold.h"
#include "geometry/so3.h"

namespace vio {
namespace {

struct ChainPoints {
  Eigen::Vector3d h_bi, h_bj, h_c;
};

// The point along the two-keyframe chain, each step scaled by rho:
// h_bi = R_b_a f_a + rho t_b_a, h_w = R_w_bi h_bi + rho p_w_bi,
// h_bj = R_w_bj^T (h_w - rho p_w_bj), h_c = R_c_b (h_bj - rho t_b_c).
// One body for the constructor and PointInTarget, so a residual-only
// evaluation gives the bits of a full one.
ChainPoints TwoKeyframePoints(const Eigen::Vector3d& f_a, double rho,
                              const Rigid& T_b_a, const Rigid& T_w_bi,
                              const Rigid& T_w_bj, const Eigen::Matrix3d& R_c_b,
                              const Eigen::Vector3d& t_b_c) {
  ChainPoints h;
  h.h_bi = T_b_a.R * f_a + rho * T_b_a.t;
  const Eigen::Vector3d h_w = T_w_bi.R * h.h_bi + rho * T_w_bi.t;
  h.h_bj = T_w_bj.R.transpose() * (h_w - rho * T_w_bj.t);
  h.h_c = R_c_b * (h.h_bj - rho * t_b_c);
  return h;
}

}  // namespace

Rigid Rigid::FromBlock(const double* x) {
  Rigid T;
  T.t = Eigen::Map<const Eigen::Vector3d>(x + kPoseTranslation);
  T.R = Eigen::Quaterniond(Eigen::Map<const Eigen::Vector4d>(x + kPoseRotation))
            .toRotationMatrix();
  return T;
}

InverseDepthChain::InverseDepthChain(const Eigen::Vector3d& f_a, double rho,
                                     const Rigid& T_b_a, const Rigid& T_w_bi,
                                     const Rigid& T_w_bj, const Rigid& T_b_c)
    : f_a_(f_a),
      rho_(rho),
      R_b_a_(T_b_a.R),
      t_b_a_(T_b_a.t),
      t_b_c_(T_b_c.t),
      p_i_minus_p_j_(T_w_bi.t - T_w_bj.t) {
  d_hc_d_hbj_ = T_b_c.R.transpose();
  d_hc_d_hw_ = d_hc_d_hbj_ * T_w_bj.R.transpose();
  d_hc_d_hbi_ = d_hc_d_hw_ * T_w_bi.R;
  const ChainPoints h =
      TwoKeyframePoints(f_a_, rho_, T_b_a, T_w_bi, T_w_bj, d_hc_d_hbj_, t_b_c_);
  h_bi_ = h.h_bi;
  h_bj_ = h.h_bj;
  h_c_ = h.h_c;
}

Eigen::Vector3d InverseDepthChain::PointInTarget(const Eigen::Vector3d& f_a,
                                                 double rho, const Rigid& T_b_a,
                                                 const Rigid& T_w_bi,
                                                 const Rigid& T_w_bj,
                                                 const Rigid& T_b_c) {
  // The two-keyframe constructor's points, without its rotation products
  // (R_c_b materialised as there, so the same bits).
  return TwoKeyframePoints(f_a, rho, T_b_a, T_w_bi, T_w_bj, T_b_c.R.transpose(),
                           T_b_c.t)
      .h_c;
}

InverseDepthChain::InverseDepthChain(const Eigen::Vector3d& f_a, double rho,
                                     const Rigid& T_b_a, const Rigid& T_b_c)
    : f_a_(f_a), rho_(rho), R_b_a_(T_b_a.R), t_b_a_(T_b_a.t), t_b_c_(T_b_c.t) {
  d_hc_d_hbj_ = T_b_c.R.transpose();
  d_hc_d_hw_.setZero();  // no world step
  d_hc_d_hbi_ = d_hc_d_hbj_;
  h_bi_ = R_b_a_ * f_a_ + rho_ * t_b_a_;
  h_bj_ = h_bi_;
  h_c_ = d_hc_d_hbj_ * (h_bj_ - rho_ * t_b_c_);
}

Matrix36 InverseDepthChain::d_h_d_pose_i() const {
  // h_w = R_w_bi h_bi + rho p_w_bi.
  // dt:     d h_w = rho dt                          -> rho d_hc_d_hw
  // dtheta: R Exp(d) h_bi ~ R h_bi - R [h_bi]x d     -> -d_hc_d_hbi [h_bi]x
  Matrix36 J;
  J.leftCols<3>() = rho_ * d_hc_d_hw_;
  J.rightCols<3>() = -d_hc_d_hbi_ * Skew(h_bi_);
  return J;
}

Matrix36 InverseDepthChain::d_h_d_pose_j() const {
  // h_bj = R_w_bj^T (h_w - rho p_w_bj).
  // dt:     d h_bj = -rho R_w_bj^T dt                -> -rho d_hc_d_hw
  // dtheta: (R Exp(d))^T = Exp(-d) R^T, so h_bj -> (I - [d]x) h_bj
  //         = h_bj + [h_bj]x d                        -> R_b_c^T [h_bj]x
  Matrix36 J;
  J.leftCols<3>() = -rho_ * d_hc_d_hw_;
  J.rightCols<3>() = d_hc_d_hbj_ * Skew(h_bj_);
  return J;
}

Matrix36 InverseDepthChain::d_h_d_anchor_extrinsic() const {
  // h_bi = R_b_a f + rho t_b_a.
  // dt:     d h_bi = rho dt                          -> rho d_hc_d_hbi
  // dtheta: R Exp(d) f ~ R f - R [f]x d               -> -d_hc_d_hbi R_b_a [f]x
  Matrix36 J;
  J.leftCols<3>() = rho_ * d_hc_d_hbi_;
  J.rightCols<3>() = -d_hc_d_hbi_ * R_b_a_ * Skew(f_a_);
  return J;
}

Matrix36 InverseDepthChain::d_h_d_target_extrinsic() const {
  // h_c = R_b_c^T (h_bj - rho t_b_c).
  // dt:     d h_c = -rho R_b_c^T dt
  // dtheta: Exp(-d) R_b_c^T (...) ~ (I - [d]x) h_c = h_c + [h_c]x d
  Matrix36 J;
  J.leftCols<3>() = -rho_ * d_hc_d_hbj_;
  J.rightCols<3>() = Skew(h_c_);
  return J;
}

Eigen::Vector3d InverseDepthChain::d_h_d_rho() const {
  // h_c is linear in rho; its rho terms are the translations of the chain:
  //   d h_c / d rho = d_hc_d_hbi t_b_a + d_hc_d_hw (p_w_bi - p_w_bj)
  //                   - R_b_c^T t_b_c
  // (d_hc_d_hw is zero in the one-keyframe chain, where the poses cancel).
  return d_hc_d_hbi_ * t_b_a_ + d_hc_d_hw_ * p_i_minus_p_j_ -
         d_hc_d_hbj_ * t_b_c_;
}

ProjectedResidual ProjectResidual(const Eigen::Vector3d& h_c,
                                  const Eigen::Vector2d& xy_c,
                                  double sqrt_info) {
  ProjectedResidual p;
  p.active = h_c.z() >= kMinProjectiveDepth;
  const double z = p.active ? h_c.z() : kMinProjectiveDepth;
  const double inv_z = 1.0 / z;
  p.r = sqrt_info * (h_c.head<2>() * inv_z - xy_c);
  if (p.active) {
    // d (h.xy / h.z) / d h = 1/z [1 0 -x/z; 0 1 -y/z].
    p.d_r_d_h << inv_z, 0.0, -h_c.x() * inv_z * inv_z,  //
        0.0, inv_z, -h_c.y() * inv_z * inv_z;
    p.d_r_d_h *= sqrt_info;
  } else {
    p.d_r_d_h.setZero();
  }
  return p;
}

Matrix36 InverseDepthChain::d_h_d_rigid(ChainBlock block) const {
  switch (block) {
    case ChainBlock::kPoseI:
      return d_h_d_pose_i();
    case ChainBlock::kPoseJ:
      return d_h_d_pose_j();
    case ChainBlock::kAnchorExtrinsic:
      return d_h_d_anchor_extrinsic();
    case ChainBlock::kTargetExtrinsic:
      return d_h_d_target_extrinsic();
    case ChainBlock::kSharedExtrinsic:
    case ChainBlock::kInverseDepth:
      break;
  }
  return d_h_d_anchor_extrinsic() + d_h_d_target_extrinsic();
}

void WriteChainJacobians(const ProjectedResidual& p,
                         const InverseDepthChain& chain,
                         std::initializer_list<ChainBlock> blocks,
                         double const* const* parameters, double** jacobians,
                         JacobianSpace space) {
  int k = 0;
  for (const ChainBlock block : blocks) {
    double* jacobian = jacobians[k];
    const double* x = parameters[k];
    ++k;
    if (jacobian == nullptr) continue;
    // r = pi(h_c): d r / d block = d_r_d_h * d_h_d_block (d_r_d_h is zero
    // when the residual is inactive).
    if (block == ChainBlock::kInverseDepth) {
      Eigen::Map<Eigen::Vector2d> d_r_d_rho(jacobian);
      d_r_d_rho = p.d_r_d_h * chain.d_h_d_rho();
    } else if (space == JacobianSpace::kTangent) {
      // Chain rule on the right perturbation [dt, dtheta] directly:
      //   d r / d [dt, dtheta] = d_r_d_h (2 x 3) * d_h_d_rigid (3 x 6),
      // row-major 2 x 6; the ambient branch below is this times
      // MinusJacobian(x), which Ceres undoes with PlusJacobian(x). Zero
      // when inactive (d_r_d_h is zero).
      Eigen::Map<Eigen::Matrix<double, 2, 6, Eigen::RowMajor>> d_r_d_block(
          jacobian);
      d_r_d_block = p.d_r_d_h * chain.d_h_d_rigid(block);
    } else if (!p.active) {
      Eigen::Map<Eigen::Matrix<double, 2, 7, Eigen::RowMajor>>(jacobian)
          .setZero();
    } else {
      const Matrix26 d_r_d_block = p.d_r_d_h * chain.d_h_d_rigid(block);
      LiftPoseJacobian(d_r_d_block, x, jacobian);
    }
  }
}

}  // namespace vio
