#ifndef VIO_FACTORS_STEREO_REPROJECTION_FACTOR_H_
#define VIO_FACTORS_STEREO_REPROJECTION_FACTOR_H_

// Stereo reprojection of an inverse-depth landmark anchored in camera 0 of
// keyframe i into camera 1, in the same keyframe or in another one.
//
//   p_c0 = f_i / rho,  f_i = (x_i, y_i, 1)   anchor observation (cam0, kf i)
//   same keyframe:   p_c1 = T_b_c1^-1 T_b_c0 p_c0
//   other keyframe:  p_c1 = T_b_c1^-1 T_w_bj^-1 T_w_bi T_b_c0 p_c0
//   r = sqrt_info * (p_c1.xy / p_c1.z - xy_c1)                   (2)
// with sqrt_info = focal / sigma_px (the target camera's focal length).
//
// Extrinsics: p_b = R_b_c p_c + t_b_c, stored like a pose (7). They are
// ordinary blocks; the estimator may hold them constant. Jacobians are derived
// on PoseManifold's tangent space and lifted through its MinusJacobian.
//
// Degenerate geometry (factors/inverse_depth_chain.h): a point behind camera
// 1 or at its centre gives a finite, clamped residual and zero Jacobians; a
// near-zero or negative rho gives smooth, finite values. Evaluate never fails.

#include <ceres/sized_cost_function.h>

#include <Eigen/Core>

#include "factors/tangent_jacobians.h"

namespace vio {

// Same keyframe. Blocks: T_b_c0 (7), T_b_c1 (7), rho [1/m] (1).
class StereoReprojectionFactor final
    : public ceres::SizedCostFunction<2, 7, 7, 1>,
      public TangentJacobians {
 public:
  enum Block { kExtrinsic0 = 0, kExtrinsic1 = 1, kInverseDepth = 2 };

  // xy_c0: anchor observation in cam0, xy_c1: the same landmark in cam1 of
  // the same keyframe, both normalised [-]; sqrt_info = focal [px] / sigma.
  StereoReprojectionFactor(const Eigen::Vector2d& xy_c0,
                           const Eigen::Vector2d& xy_c1, double sqrt_info);

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;
  bool EvaluateTangent(double const* const* parameters, double* residuals,
                       double** jacobians) const override;

 private:
  // Evaluate (tangent false) or EvaluateTangent (tangent true).
  bool Compute(double const* const* parameters, double* residuals,
               double** jacobians, bool tangent) const;

  Eigen::Vector3d f_i_;
  Eigen::Vector2d xy_c1_;
  double sqrt_info_;
};

// Another keyframe. Blocks: pose_i T_w_bi (7), pose_j T_w_bj (7),
// T_b_c0 (7), T_b_c1 (7), rho [1/m] (1).
class StereoTwoFrameReprojectionFactor final
    : public ceres::SizedCostFunction<2, 7, 7, 7, 7, 1>,
      public TangentJacobians {
 public:
  enum Block {
    kPoseI = 0,
    kPoseJ = 1,
    kExtrinsic0 = 2,
    kExtrinsic1 = 3,
    kInverseDepth = 4
  };

  // xy_i: anchor observation in cam0 of keyframe i; xy_j: the landmark in
  // cam1 of keyframe j, both normalised [-]; sqrt_info = focal [px] / sigma.
  StereoTwoFrameReprojectionFactor(const Eigen::Vector2d& xy_i,
                                   const Eigen::Vector2d& xy_j,
                                   double sqrt_info);

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;
  bool EvaluateTangent(double const* const* parameters, double* residuals,
                       double** jacobians) const override;

 private:
  // Evaluate (tangent false) or EvaluateTangent (tangent true).
  bool Compute(double const* const* parameters, double* residuals,
               double** jacobians, bool tangent) const;

  Eigen::Vector3d f_i_;
  Eigen::Vector2d xy_j_;
  double sqrt_info_;
};

}  // namespace vio

#endif  // VIO_FACTORS_STEREO_REPROJECTION_FACTOR_H_
