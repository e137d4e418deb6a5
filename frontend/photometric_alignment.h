#ifndef VIO_FRONTEND_PHOTOMETRIC_ALIGNMENT_H_
#define VIO_FRONTEND_PHOTOMETRIC_ALIGNMENT_H_

// The least-squares problem of the notes' frame tracking (seeds/000, eqs.
// 1-4) at one pyramid level: every depth point of the keyframe (host) is
// warped into one or two images of the tracked frame (target) by the
// relative pose delta = T_t_h (target camera from host camera), and
//
//   f_m   = e^(a_k) I_h(p_m) - (I_k(w_m) - b_k)              (notes' f_m,
//                                                            DSO's brightness)
//   w_m   = K_k pi(h_k),  h_k = R_k (R f_m + rho_m t) + rho_m t_k
//   W_m   = lambda_k (2 sigma_I^2 + (d f_m / d rho)^2 V_m)^-1  (notes' W_m)
//   E     = sum_m rho_H(W_m f_m^2)                           (notes' E(delta))
//
// f_m = K_h^-1 p_m is the host pixel's bearing and rho_m its inverse depth,
// so R f + rho t = rho * (the point in the target camera): the homogeneous
// form, finite for far points. Target k is the frame's left image (T_k = I,
// lambda_k = 1) or its right image (T_k = T_r_l, lambda_k = the notes' lambda
// of the stereo term E_s, which ties the two images of the frame through the
// fixed rig). rho_H is the Huber kernel on sqrt(W) f (huber_scale, 0: none).
//
// Unknowns, in this order: the right perturbation of delta (DESIGN.md),
//   t (+) dt = t + dt,  R (+) dtheta = R Exp(dtheta),
// then (a, b) of each target image when estimate_affine. The Jacobian rows
// and the weights are derived in photometric_alignment.cc; the notes' own
// (left-perturbation) row and its corrections are in docs/direct.md.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "frontend/direct_options.h"
#include "frontend/image_pyramid.h"
#include "frontend/stereo_depth.h"

namespace vio {

// What TrackFrame solves for.
struct AlignmentState {
  Eigen::Isometry3d T_t_h = Eigen::Isometry3d::Identity();  // the notes' delta
  // (a, b) of the target's left [0] and right [1] image, relative to the
  // keyframe image (whose own a = b = 0).
  Eigen::Vector2d affine[2] = {Eigen::Vector2d::Zero(),
                               Eigen::Vector2d::Zero()};
};

// One image of the tracked frame at the level being aligned.
struct AlignmentTarget {
  const PyramidLevel* level = nullptr;
  Eigen::Isometry3d T_k_t = Eigen::Isometry3d::Identity();  // from the left
  double weight = 1.0;                                      // lambda_k
  int affine = 0;  // which (a, b) of AlignmentState it uses
};

// One residual with its derivatives.
struct AlignmentResidual {
  double f = 0.0;                          // [grey]
  double weight = 0.0;                     // W_m (lambda_k included) [1/grey^2]
  double d_f_d_rho = 0.0;                  // [grey m]
  Eigen::Matrix<double, 1, 6> d_f_d_pose;  // [dt, dtheta]
  Eigen::Vector2d d_f_d_affine = Eigen::Vector2d::Zero();  // (a_k, b_k)
};

// The normal equations of the notes at one state (eq. 4):
//   H = sum_m J_m^T w_m J_m,  g = sum_m J_m^T w_m f_m,  H delta* = -g
// with w_m = W_m times the Huber weight (IRLS), and the mean robust cost.
struct AlignmentLinearization {
  Eigen::MatrixXd H;
  Eigen::VectorXd g;
  double error = 0.0;  // E / number of residuals [-]
  int residuals = 0;   // residuals inside their target image
};

class PhotometricAlignment {
 public:
  // The most unknowns: the pose and two brightness pairs.
  static constexpr int kMaxUnknowns = 10;

  // `points` and `host_camera` are the keyframe's level (the points are
  // referred to, not copied: they must outlive the object); the options give
  // sigma_I, the weight, the kernel and whether (a, b) are unknowns.
  PhotometricAlignment(const std::vector<DepthPoint>& points,
                       const Pinhole& host_camera,
                       std::vector<AlignmentTarget> targets,
                       const DirectTrackerOptions& options);

  int num_unknowns() const { return 6 + 2 * num_affine_; }
  int num_affine() const { return num_affine_; }
  const std::vector<DepthPoint>& points() const { return points_; }
  const Pinhole& host_camera() const { return host_camera_; }
  const DirectTrackerOptions& options() const { return options_; }
  const std::vector<AlignmentTarget>& targets() const { return targets_; }

  // The residual of point m in target k at a state; false when it is
  // inactive (behind the target camera, or not inside its image by the
  // bicubic margin).
  bool Residual(size_t m, size_t k, const AlignmentState& state,
                AlignmentResidual* r) const;

  // Error, and with `normal_equations` also H and g, over all residuals.
  AlignmentLinearization Linearize(const AlignmentState& state,
                                   bool normal_equations) const;

  // state (+) step, step laid out as the unknowns.
  AlignmentState Plus(const AlignmentState& state,
                      const Eigen::VectorXd& step) const;

  // The fraction of the points whose residual in target 0 is active.
  double Overlap(const AlignmentState& state) const;

 private:
  const std::vector<DepthPoint>& points_;
  Pinhole host_camera_;
  std::vector<AlignmentTarget> targets_;
  DirectTrackerOptions options_;
  int num_affine_ = 0;  // (a, b) pairs among the unknowns
};

// Huber cost rho_H(s) of a squared weighted residual s, and its IRLS weight
// rho_H'(s) (1 inside the kernel); scale 0 means no kernel.
double HuberCost(double s, double scale);
double HuberWeight(double s, double scale);

}  // namespace vio

#endif  // VIO_FRONTEND_PHOTOMETRIC_ALIGNMENT_H_
