#ifndef VIO_FACTORS_POSE_MANIFOLD_H_
#define VIO_FACTORS_POSE_MANIFOLD_H_

// The manifold of pose and extrinsic parameter blocks (DESIGN.md):
//   ambient x = [t (3), q (x, y, z, w)] (7),  tangent d = [dt (3), dtheta (3)]
//   (6) x (+) d   = [t + dt,  q (x) Exp(dtheta)]      (right perturbation, full
//   angle) y (-) x   = [t_y - t_x,  Log(q_x^-1 (x) q_y)]
//
// How the factors' Jacobians fit together with it. Ceres multiplies the
// Jacobian a cost function returns for a block (r x 7, "ambient") by
// PlusJacobian(x) (7 x 6) to get the Jacobian in the tangent space. Our factors
// derive tangent Jacobians J_tan = d r / d d (r x 6) by hand and return
//   J_amb = J_tan * MinusJacobian(x)                   (r x 7),
// where MinusJacobian(x) = d (y (-) x) / d y at y = x. Since
// MinusJacobian(x) * PlusJacobian(x) = I_6 (checked by the manifold tests),
// Ceres sees J_amb * PlusJacobian = J_tan exactly: the solver, the covariance
// estimation and the gradient checker all work with the true tangent Jacobian.
// (VINS-Mono instead pads J_tan with a zero column and returns [I; 0] as the
// plus Jacobian; that is only right at q = identity and fools GradientChecker.)
//
// Ceres' EigenQuaternionManifold perturbs on the left with a half-angle delta;
// never mix it with this one.

#include <ceres/manifold.h>

#include <Eigen/Core>

namespace vio {

// Tangent layout of a pose.
constexpr int kPoseAmbientSize = 7;
constexpr int kPoseTangentSize = 6;
constexpr int kPoseTranslation = 0;  // t (3), both in ambient and tangent
constexpr int kPoseRotation = 3;     // q (4) ambient, dtheta (3) tangent

using PoseMinusJacobian = Eigen::Matrix<double, 6, 7, Eigen::RowMajor>;
using PosePlusJacobian = Eigen::Matrix<double, 7, 6, Eigen::RowMajor>;

class PoseManifold final : public ceres::Manifold {
 public:
  int AmbientSize() const override { return kPoseAmbientSize; }
  int TangentSize() const override { return kPoseTangentSize; }

  bool Plus(const double* x, const double* delta,
            double* x_plus_delta) const override;
  // 7 x 6, row-major.
  bool PlusJacobian(const double* x, double* jacobian) const override;
  bool Minus(const double* y, const double* x,
             double* y_minus_x) const override;
  // 6 x 7, row-major.
  bool MinusJacobian(const double* x, double* jacobian) const override;

  // The same Jacobians as Eigen matrices, for the factors' lifting step.
  static PoseMinusJacobian MinusJacobianAt(const double* x);
  static PosePlusJacobian PlusJacobianAt(const double* x);
};

// Lifts a tangent Jacobian (rows x 6) of a pose block into the ambient
// Jacobian (rows x 7, row-major) that Ceres expects from Evaluate.
template <typename TangentJacobian>
void LiftPoseJacobian(const TangentJacobian& d_r_d_tangent, const double* x,
                      double* ambient_jacobian) {
  constexpr int kRows = TangentJacobian::RowsAtCompileTime;
  Eigen::Map<Eigen::Matrix<double, kRows, 7, Eigen::RowMajor>> out(
      ambient_jacobian);
  out = d_r_d_tangent * PoseManifold::MinusJacobianAt(x);
}

}  // namespace vio

#endif  // VIO_FACTORS_POSE_MANIFOLD_H_
