#include "frontend/photometric_alignment.h"

#include <cmath>
#include <utility>

#include "factors/inverse_depth_chain.h"
#include "factors/photometric_factor.h"
#include "geometry/so3.h"

namespace vio {

double HuberCost(double s, double scale) {
  if (scale <= 0.0 || s <= scale * scale) return s;
  return 2.0 * scale * std::sqrt(s) - scale * scale;
}

double HuberWeight(double s, double scale) {
  if (scale <= 0.0 || s <= scale * scale) return 1.0;
  return scale / std::sqrt(s);
}

PhotometricAlignment::PhotometricAlignment(
    const std::vector<DepthPoint>& points, const Pinhole& host_camera,
    std::vector<AlignmentTarget> targets, const DirectTrackerOptions& options)
    : points_(points),
      host_camera_(host_camera),
      targets_(std::move(targets)),
      options_(options) {
  if (options_.estimate_affine) {
    for (const AlignmentTarget& t : targets_) {
      num_affine_ = std::max(num_affine_, t.affine + 1);
    }
  }
}

bool PhotometricAlignment::Residual(size_t m, size_t k,
                                    const AlignmentState& state,
                                    AlignmentResidual* r) const {
  const DepthPoint& p = points_[m];
  const AlignmentTarget& target = targets_[k];
  const Eigen::Matrix3d& R = state.T_t_h.linear();
  const Eigen::Vector3d& t = state.T_t_h.translation();
  const Eigen::Matrix3d& R_k = target.T_k_t.linear();
  const Eigen::Vector3d& t_k = target.T_k_t.translation();
  // h = rho q = R f + rho t (the notes' q = exp(delta) P, scaled by rho), and
  // in target camera k: h_k = R_k h + rho t_k.
  const Eigen::Vector3d f = host_camera_.Bearing(p.uv);
  const Eigen::Vector3d h_k = R_k * (R * f + p.rho * t) + p.rho * t_k;
  if (!(h_k.z() >= kMinProjectiveDepth)) return false;
  const Pinhole& K = target.level->camera;
  const Eigen::Vector2d w = K.Project(h_k);
  const ImageGrid& image = *target.level->image;
  if (!image.Inside(w.x(), w.y(), kImageGridMargin)) return false;
  double I = 0.0;
  Eigen::RowVector2d g;  // [dI/du, dI/dv] at w
  image.Evaluate(w.x(), w.y(), &I, &g[0], &g[1]);
  const Eigen::Vector2d& ab = state.affine[target.affine];
  const double e = std::exp(ab[0]);
  r->f = e * p.intensity - (I - ab[1]);
  // Chain rule, the notes' eq. 2 with the intrinsics and the right
  // perturbation:
  //   d f / d h_k = -g d w / d h_k,  d w / d h_k = K pi'(h_k)     (1 x 3)
  //   dt:     t + dt      -> h_k + rho R_k dt
  //   dtheta: R Exp(d) f ~ R f + R [d]x f = R f - R [f]x d
  //                       -> h_k - R_k R [f]x dtheta
  //   rho:    d h_k / d rho = R_k t + t_k       (h_k is linear in rho)
  const Eigen::RowVector3d d_f_d_h = -g * K.ProjectJacobian(h_k);
  const Eigen::RowVector3d d_f_d_h_t = d_f_d_h * R_k;  // w.r.t. h
  r->d_f_d_pose.leftCols<3>() = p.rho * d_f_d_h_t;
  r->d_f_d_pose.rightCols<3>() = -d_f_d_h_t * R * Skew(f);
  r->d_f_d_rho = d_f_d_h_t.dot(t) + d_f_d_h.dot(t_k);
  // f = e^a I_h - I_k + b:  d f / d a = e^a I_h,  d f / d b = 1.
  r->d_f_d_affine = Eigen::Vector2d(e * p.intensity, 1.0);
  // The notes' weight: the inverse depth's variance V reaches f through
  // d f / d rho; lambda_k scales the stereo term.
  const double d_rho = options_.variance_weight ? r->d_f_d_rho : 0.0;
  r->weight = target.weight *
              PhotometricWeight(options_.sigma_intensity, d_rho, p.variance);
  return true;
}

AlignmentLinearization PhotometricAlignment::Linearize(
    const AlignmentState& state, bool normal_equations) const {
  // Accumulated in fixed-size blocks of the largest layout (6 pose + two
  // brightness pairs); the unknowns in use are the leading ones.
  using Row = Eigen::Matrix<double, 1, kMaxUnknowns>;
  Eigen::Matrix<double, kMaxUnknowns, kMaxUnknowns> H;
  Eigen::Matrix<double, kMaxUnknowns, 1> g;
  H.setZero();
  g.setZero();
  AlignmentLinearization lin;
  double cost = 0.0;
  Row J;
  for (size_t m = 0; m < points_.size(); ++m) {
    for (size_t k = 0; k < targets_.size(); ++k) {
      AlignmentResidual r;
      if (!Residual(m, k, state, &r)) continue;
      const double s = r.weight * r.f * r.f;
      cost += HuberCost(s, options_.huber_scale);
      ++lin.residuals;
      if (!normal_equations) continue;
      J.setZero();
      J.head<6>() = r.d_f_d_pose;
      if (num_affine_ > 0) {
        J.segment<2>(6 + 2 * targets_[k].affine) = r.d_f_d_affine.transpose();
      }
      // IRLS: the Huber kernel's weight rho'(s) joins W_m.
      const double w = r.weight * HuberWeight(s, options_.huber_scale);
      H.selfadjointView<Eigen::Lower>().rankUpdate(J.transpose(), w);
      g.noalias() += (w * r.f) * J.transpose();
    }
  }
  if (normal_equations) {
    const int n = num_unknowns();
    lin.H = H.topLeftCorner(n, n).selfadjointView<Eigen::Lower>();
    lin.g = g.head(n);
  }
  lin.error = lin.residuals > 0 ? cost / lin.residuals : 0.0;
  return lin;
}

AlignmentState PhotometricAlignment::Plus(const AlignmentState& state,
                                          const Eigen::VectorXd& step) const {
  AlignmentState out = state;
  out.T_t_h.translation() += step.head<3>();
  // Through a unit quaternion, so the rotation stays orthonormal however
  // many steps and compositions it goes through (a drift there would be
  // amplified by every Isometry3d::inverse(), which transposes).
  out.T_t_h.linear() =
      Eigen::Quaterniond(state.T_t_h.linear() * Exp(step.segment<3>(3)))
          .normalized()
          .toRotationMatrix();
  for (int a = 0; a < num_affine_; ++a) {
    out.affine[a] += step.segment<2>(6 + 2 * a);
  }
  return out;
}

double PhotometricAlignment::Overlap(const AlignmentState& state) const {
  if (points_.empty() || targets_.empty()) return 0.0;
  int inside = 0;
  AlignmentResidual r;
  for (size_t m = 0; m < points_.size(); ++m) {
    if (Residual(m, 0, state, &r)) ++inside;
  }
  return static_cast<double>(inside) / points_.size();
}

}  // namespace vio
