#ifndef VIO_FACTORS_REPROJECTION_FACTOR_H_
#define VIO_FACTORS_REPROJECTION_FACTOR_H_

// Monocular reprojection of an inverse-depth landmark into another keyframe
// seen by the same camera (VINS-Mono's ProjectionFactor, on our conventions).
//
//   p_c_i = f_i / rho,  f_i = (x_i, y_i, 1)   anchor observation in keyframe i
//   p_c_j = T_b_c^-1 T_w_bj^-1 T_w_bi T_b_c p_c_i
//   r     = sqrt_info * (p_c_j.xy / p_c_j.z - xy_j)            (2)
// with sqrt_info = focal / sigma_px, so r is in units of sigma.
//
// Parameter blocks, in this order:
//   pose_i  T_w_bi (7) [t, q(x, y, z, w)]
//   pose_j  T_w_bj (7)
//   T_b_c   the camera extrinsic (7), p_b = R_b_c p_c + t_b_c
//   rho     inverse depth of the landmark in camera i [1/m] (1)
// Jacobians are derived on the tangent spaces of PoseManifold (right
// perturbation) and lifted to the ambient 7 columns through MinusJacobian.
//
// Degenerate geometry (factors/inverse_depth_chain.h): a point behind camera
// j or at its centre gives a finite, clamped residual and zero Jacobians; a
// near-zero or negative rho gives smooth, finite values. Evaluate never fails.

#include <ceres/sized_cost_function.h>

#include <Eigen/Core>

#include "factors/tangent_jacobians.h"

namespace vio {

class ReprojectionFactor final : public ceres::SizedCostFunction<2, 7, 7, 7, 1>,
                                 public TangentJacobians {
 public:
  enum Block { kPoseI = 0, kPoseJ = 1, kExtrinsic = 2, kInverseDepth = 3 };

  // xy_i, xy_j: undistorted normalised coordinates [-] of the landmark in
  // keyframe i (its anchor) and j; sqrt_info = focal [px] / sigma [px].
  ReprojectionFactor(const Eigen::Vector2d& xy_i, const Eigen::Vector2d& xy_j,
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

#endif  // VIO_FACTORS_REPROJECTION_FACTOR_H_
