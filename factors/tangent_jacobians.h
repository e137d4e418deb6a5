#ifndef VIO_FACTORS_TANGENT_JACOBIANS_H_
#define VIO_FACTORS_TANGENT_JACOBIANS_H_

// Factors derive their Jacobians in the tangent space of each block (the
// project's right perturbation, pose_manifold.h) and lift them for Ceres:
//   J_amb = J_tan * MinusJacobian(x)          (rows x 7 per pose block)
// after which Ceres (or any solver working in the tangent space) multiplies
// by PlusJacobian(x) to get J_tan back. A factor that also implements this
// interface hands a tangent-space solver (estimator/window_solver.h) J_tan
// directly, saving both products and MinusJacobian per pose block and
// evaluation. The numbers are the same: J_tan is what Evaluate lifts (the
// visual factors' tests hold J_tan = J_amb * PlusJacobian).

namespace vio {

class TangentJacobians {
 public:
  virtual ~TangentJacobians() = default;

  // As ceres::CostFunction::Evaluate, but jacobians[k] (when jacobians and
  // jacobians[k] are not null) receives d r / d (tangent perturbation of
  // block k), row-major: rows x 6 for a pose or extrinsic block, rows x size
  // for a Euclidean block.
  virtual bool EvaluateTangent(double const* const* parameters,
                               double* residuals, double** jacobians) const = 0;
};

}  // namespace vio

#endif  // VIO_FACTORS_TANGENT_JACOBIANS_H_
