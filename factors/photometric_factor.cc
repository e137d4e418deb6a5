#include "factors/photometric_factor.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "factors/pose_manifold.h"

namespace vio {

double PhotometricWeight(double sigma_intensity, double d_f_d_rho,
                         double rho_variance) {
  // The pixel's two intensities each carry sigma_I^2; the inverse depth's
  // variance V reaches f through df/drho (first-order propagation).
  return 1.0 / (2.0 * sigma_intensity * sigma_intensity +
                d_f_d_rho * d_f_d_rho * rho_variance);
}

PhotometricFactor::PhotometricFactor(const PhotometricHost& host,
                                     std::shared_ptr<const ImageGrid> target,
                                     const Pinhole& target_camera,
                                     const Rigid& T_b_a, const Rigid& T_b_c,
                                     double sqrt_weight)
    : f_a_(host.camera.Bearing(host.uv)),
      intensity_(host.intensity),
      target_(std::move(target)),
      target_camera_(target_camera),
      T_b_a_(T_b_a),
      T_b_c_(T_b_c),
      sqrt_weight_(sqrt_weight) {}

bool PhotometricFactor::Linearize(const Eigen::Vector3d& h_c, double a_i,
                                  double b_i, double a_j, double b_j, double* f,
                                  Eigen::RowVector3d* d_f_d_h) const {
  if (!(h_c.z() >= kMinProjectiveDepth)) return false;
  const Eigen::Vector2d w = target_camera_.Project(h_c);
  if (!target_->Inside(w.x(), w.y(), kImageGridMargin)) return false;
  double I_j = 0.0;
  Eigen::RowVector2d g;  // image gradient [dI/du, dI/dv] at w
  target_->Evaluate(w.x(), w.y(), &I_j, &g[0], &g[1]);
  *f = std::exp(a_j - a_i) * (intensity_ - b_i) - (I_j - b_j);
  // f depends on h only through -I_j(w(h)):
  //   d f / d h = -g * d w / d h,  d w / d h = K pi'(h) (geometry/pinhole.h).
  *d_f_d_h = -g * target_camera_.ProjectJacobian(h_c);
  return true;
}

bool PhotometricFactor::InverseDepthDerivative(double const* const* parameters,
                                               double* f,
                                               double* d_f_d_rho) const {
  const InverseDepthChain chain(f_a_, parameters[kInverseDepth][0], T_b_a_,
                                Rigid::FromBlock(parameters[kPoseI]),
                                Rigid::FromBlock(parameters[kPoseJ]), T_b_c_);
  Eigen::RowVector3d d_f_d_h;
  if (!Linearize(chain.h_c(), parameters[kAffineI][0], parameters[kAffineI][1],
                 parameters[kAffineJ][0], parameters[kAffineJ][1], f,
                 &d_f_d_h)) {
    return false;
  }
  *d_f_d_rho = d_f_d_h * chain.d_h_d_rho();
  return true;
}

bool PhotometricFactor::Evaluate(double const* const* parameters,
                                 double* residuals, double** jacobians) const {
  const double rho = parameters[kInverseDepth][0];
  const double a_i = parameters[kAffineI][0], b_i = parameters[kAffineI][1];
  const double a_j = parameters[kAffineJ][0], b_j = parameters[kAffineJ][1];
  if (!std::isfinite(rho + a_i + b_i + a_j + b_j)) return false;
  const InverseDepthChain chain(f_a_, rho, T_b_a_,
                                Rigid::FromBlock(parameters[kPoseI]),
                                Rigid::FromBlock(parameters[kPoseJ]), T_b_c_);
  if (!chain.h_c().allFinite()) return false;
  double f = 0.0;
  Eigen::RowVector3d d_f_d_h;
  const bool active = Linearize(chain.h_c(), a_i, b_i, a_j, b_j, &f, &d_f_d_h);
  const double s = sqrt_weight_;
  residuals[0] = active ? s * f : 0.0;
  if (jacobians == nullptr) return true;

  const int sizes[] = {7, 7, 1, 2, 2};
  if (!active) {
    for (int k = 0; k < 5; ++k) {
      if (jacobians[k] != nullptr) {
        std::fill(jacobians[k], jacobians[k] + sizes[k], 0.0);
      }
    }
    return true;
  }
  // Pose blocks: d r / d [dt, dtheta] = s * d f / d h * d h / d pose, with
  // d h / d pose from the inverse-depth chain (right perturbation, derived in
  // factors/inverse_depth_chain.cc), lifted to the 7 ambient columns.
  if (jacobians[kPoseI] != nullptr) {
    const Eigen::Matrix<double, 1, 6> d = s * d_f_d_h * chain.d_h_d_pose_i();
    LiftPoseJacobian(d, parameters[kPoseI], jacobians[kPoseI]);
  }
  if (jacobians[kPoseJ] != nullptr) {
    const Eigen::Matrix<double, 1, 6> d = s * d_f_d_h * chain.d_h_d_pose_j();
    LiftPoseJacobian(d, parameters[kPoseJ], jacobians[kPoseJ]);
  }
  // h is linear in rho (d h / d rho = the chain's translations), and the
  // projection is scale invariant, so d r / d rho = s * d f / d h * d h/d rho.
  if (jacobians[kInverseDepth] != nullptr) {
    jacobians[kInverseDepth][0] = s * d_f_d_h.dot(chain.d_h_d_rho());
  }
  // Brightness: with e = exp(a_j - a_i) and c = e (I_i - b_i),
  //   d f / d a_i = -c,  d f / d b_i = -e,  d f / d a_j = c,  d f / d b_j = 1.
  const double e = std::exp(a_j - a_i);
  const double c = e * (intensity_ - b_i);
  if (jacobians[kAffineI] != nullptr) {
    jacobians[kAffineI][0] = -s * c;
    jacobians[kAffineI][1] = -s * e;
  }
  if (jacobians[kAffineJ] != nullptr) {
    jacobians[kAffineJ][0] = s * c;
    jacobians[kAffineJ][1] = s;
  }
  return true;
}

}  // namespace vio
