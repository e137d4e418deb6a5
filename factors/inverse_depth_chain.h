#ifndef VIO_FACTORS_INVERSE_DEPTH_CHAIN_H_
#define VIO_FACTORS_INVERSE_DEPTH_CHAIN_H_

// The chain shared by every visual factor: a landmark held as inverse depth
// rho in its anchor camera a (its first observation, normalised bearing
// f = (x_a, y_a, 1)) is carried into a target camera c and projected there.
//
// The chain is written on the homogeneous point h = rho * p, which names the
// same image point as p (projection is scale invariant) but stays finite as
// rho -> 0 (a point at infinity) and is linear in rho:
//   h_a  = f                                   (= rho * p_a)
//   h_bi = R_b_a f + rho t_b_a                 anchor camera -> body i
//   h_w  = R_w_bi h_bi + rho p_w_bi            body i -> world
//   h_bj = R_w_bj^T (h_w - rho p_w_bj)         world -> body j
//   h_c  = R_b_c^T (h_bj - rho t_b_c)          body j -> target camera
// When the target is the other camera of the same keyframe (stereo in one
// frame) the world step is skipped: h_bj = h_bi.
//
// Rigid blocks (poses T_w_b and extrinsics T_b_c, DESIGN.md) are perturbed on
// the right: t (+) dt = t + dt, R (+) dtheta = R Exp(dtheta). The derivatives
// below are with respect to those tangent perturbations [dt, dtheta] (3 x 6).
//
// Projection and its degenerate cases (ProjectResidual):
//   r = sqrt_info * (h_c.xy / h_c.z - xy_c),  sqrt_info = focal / sigma_px.
// h_c.z = rho * z_c is the target depth over the anchor depth ("projective
// depth"). It is small or negative exactly when the point is behind the
// target camera, at its centre or at 90 degrees from its axis. Below
// kMinProjectiveDepth the factor is inactive: the residual is computed with
// h_c.z clamped to kMinProjectiveDepth (a large but finite value) and every
// Jacobian is zero, so the point neither pulls the states nor yields NaN.
// A near-zero or negative rho is not singular in this form: the residual and
// its Jacobians stay smooth and finite through rho = 0; deciding what to do
// with a landmark whose rho ends up <= 0 is the estimator's business.

#include <Eigen/Core>
#include <initializer_list>

namespace vio {

// Below this projective depth h_c.z = rho * z_c [-] a point counts as behind
// (or at the centre of) the target camera; see the header comment.
constexpr double kMinProjectiveDepth = 1e-3;

using Matrix23 = Eigen::Matrix<double, 2, 3>;
using Matrix26 = Eigen::Matrix<double, 2, 6>;
using Matrix36 = Eigen::Matrix<double, 3, 6>;

// The role a factor's parameter block plays in the chain.
enum class ChainBlock {
  kPoseI,            // T_w_bi (7)
  kPoseJ,            // T_w_bj (7)
  kAnchorExtrinsic,  // T_b_a (7)
  kTargetExtrinsic,  // T_b_c (7)
  kSharedExtrinsic,  // one camera is anchor and target: T_b_a = T_b_c (7)
  kInverseDepth,     // rho (1)
};

// A rigid transform read from a 7-block [t (3), q (x, y, z, w)]: maps points
// from its second frame to its first (T_w_b: p_w = R p_b + t).
struct Rigid {
  Eigen::Matrix3d R;
  Eigen::Vector3d t;
  static Rigid FromBlock(const double* x);
};

// The homogeneous point of one observation in its target camera, and its
// derivatives with respect to every block's tangent perturbation. Build it
// once per Evaluate; each derivative is computed only when asked for.
class InverseDepthChain {
 public:
  // Two keyframes: anchor camera a on body i, target camera c on body j.
  InverseDepthChain(const Eigen::Vector3d& f_a, double rho, const Rigid& T_b_a,
                    const Rigid& T_w_bi, const Rigid& T_w_bj,
                    const Rigid& T_b_c);
  // One keyframe: anchor camera a and target camera c on the same body.
  InverseDepthChain(const Eigen::Vector3d& f_a, double rho, const Rigid& T_b_a,
                    const Rigid& T_b_c);

  // h_c, the point in the target camera scaled by rho.
  const Eigen::Vector3d& h_c() const { return h_c_; }
  // The two-keyframe constructor's h_c alone, without the rotation products
  // only its derivatives need: for residual-only evaluations (a trust-region
  // step's candidate cost). The same arithmetic, so the same bits.
  static Eigen::Vector3d PointInTarget(const Eigen::Vector3d& f_a, double rho,
                                       const Rigid& T_b_a, const Rigid& T_w_bi,
                                       const Rigid& T_w_bj, const Rigid& T_b_c);

  // d h_c / d [dt, dtheta] of pose i and pose j (two-keyframe chain only).
  Matrix36 d_h_d_pose_i() const;
  Matrix36 d_h_d_pose_j() const;
  // d h_c / d [dt, dtheta] of the anchor and the target camera's extrinsic.
  // When both are one block (mono), its Jacobian is their sum.
  Matrix36 d_h_d_anchor_extrinsic() const;
  Matrix36 d_h_d_target_extrinsic() const;
  // d h_c / d rho.
  Eigen::Vector3d d_h_d_rho() const;
  // d h_c / d [dt, dtheta] of a rigid block by its role; a shared extrinsic
  // enters the chain twice, so its derivative is the sum of both paths.
  Matrix36 d_h_d_rigid(ChainBlock block) const;
  // d h_c / d f_a (the anchor bearing), used for the time offset.
  Eigen::Matrix3d d_h_d_bearing() const { return d_hc_d_hbi_ * R_b_a_; }

 private:
  Eigen::Vector3d f_a_;
  double rho_;
  Eigen::Matrix3d R_b_a_;
  Eigen::Vector3d t_b_a_;
  Eigen::Vector3d t_b_c_;
  Eigen::Vector3d p_i_minus_p_j_ = Eigen::Vector3d::Zero();  // p_w_bi - p_w_bj
  Eigen::Vector3d h_bi_, h_bj_, h_c_;
  Eigen::Matrix3d d_hc_d_hbj_;  // R_b_c^T
  Eigen::Matrix3d d_hc_d_hw_;   // R_b_c^T R_w_bj^T (two keyframes only)
  Eigen::Matrix3d d_hc_d_hbi_;  // d_hc_d_hw R_w_bi, or R_b_c^T in one frame
};

// The weighted residual of h_c against the measured normalised coordinate
// xy_c, with the degenerate-geometry rule of the header comment.
struct ProjectedResidual {
  Eigen::Vector2d r;
  Matrix23 d_r_d_h;  // zero when inactive
  bool active;       // false: behind / at the centre of the target camera
};
ProjectedResidual ProjectResidual(const Eigen::Vector3d& h_c,
                                  const Eigen::Vector2d& xy_c,
                                  double sqrt_info);

// Where the rigid blocks' Jacobians are written: lifted to the ambient
// 2 x 7 row-major layout Ceres expects (PoseManifold), or left in the
// tangent space, 2 x 6 (factors/tangent_jacobians.h).
enum class JacobianSpace { kAmbient, kTangent };

// Writes d r / d block = d_r_d_h * d_h_d_block for each requested block.
// blocks[k] is the role of parameter block k; rigid Jacobians go into the
// layout of `space`, rho's is 2 x 1. All are zero when the residual is
// inactive.
void WriteChainJacobians(const ProjectedResidual& p,
                         const InverseDepthChain& chain,
                         std::initializer_list<ChainBlock> blocks,
                         double const* const* parameters, double** jacobians,
                         JacobianSpace space = JacobianSpace::kAmbient);

}  // namespace vio

#endif  // VIO_FACTORS_INVERSE_DEPTH_CHAIN_H_
