#include "test/testing/pose_test_factors.h"

#include "factors/pose_manifold.h"
#include "geometry/so3.h"

namespace vio {
namespace testing {
namespace {

Eigen::Quaterniond RotationOf(const double* x) {
  return Eigen::Quaterniond(Eigen::Map<const Eigen::Vector4d>(x + 3));
}

}  // namespace

bool RelativePoseTestFactor::Evaluate(double const* const* parameters,
                                      double* residuals,
                                      double** jacobians) const {
  const double* x_i = parameters[0];
  const double* x_j = parameters[1];
  const Eigen::Map<const Eigen::Vector3d> t_i(x_i), t_j(x_j);
  const Eigen::Quaterniond q_i = RotationOf(x_i), q_j = RotationOf(x_j);
  const Eigen::Matrix3d R_i_T = q_i.toRotationMatrix().transpose();
  const Eigen::Vector3d d = R_i_T * (t_j - t_i);
  const Eigen::Vector3d phi = Log(q_ij_.conjugate() * q_i.conjugate() * q_j);
  Eigen::Matrix<double, 6, 1> r;
  r << d - t_ij_, phi;
  Eigen::Map<Eigen::Matrix<double, 6, 1>> residual(residuals);
  residual = W_ * r;
  if (jacobians == nullptr) return true;
  const Eigen::Matrix3d Jr_inv = RightJacobianInverse(phi);
  if (jacobians[0] != nullptr) {
    // (R_i Exp(a))^T u ~ R_i^T u + [R_i^T u]x a;  E Exp(-R_j^T R_i a).
    Matrix6d d_r_d_i = Matrix6d::Zero();
    d_r_d_i.block<3, 3>(0, 0) = -R_i_T;
    d_r_d_i.block<3, 3>(0, 3) = Skew(d);
    d_r_d_i.block<3, 3>(3, 3) =
        -Jr_inv * (R_i_T * q_j.toRotationMatrix()).transpose();
    LiftPoseJacobian(Matrix6d(W_ * d_r_d_i), x_i, jacobians[0]);
  }
  if (jacobians[1] != nullptr) {
    // t_j enters linearly; E Exp(a) -> phi + Jr^-1(phi) a.
    Matrix6d d_r_d_j = Matrix6d::Zero();
    d_r_d_j.block<3, 3>(0, 0) = R_i_T;
    d_r_d_j.block<3, 3>(3, 3) = Jr_inv;
    LiftPoseJacobian(Matrix6d(W_ * d_r_d_j), x_j, jacobians[1]);
  }
  return true;
}

bool PosePriorTestFactor::Evaluate(double const* const* parameters,
                                   double* residuals,
                                   double** jacobians) const {
  const double* x = parameters[0];
  const Eigen::Vector3d phi = Log(q_m_.conjugate() * RotationOf(x));
  Eigen::Matrix<double, 6, 1> r;
  r << Eigen::Map<const Eigen::Vector3d>(x) - t_m_, phi;
  Eigen::Map<Eigen::Matrix<double, 6, 1>> residual(residuals);
  residual = W_ * r;
  if (jacobians != nullptr && jacobians[0] != nullptr) {
    Matrix6d d_r_d_x = Matrix6d::Identity();
    d_r_d_x.block<3, 3>(3, 3) = RightJacobianInverse(phi);
    LiftPoseJacobian(Matrix6d(W_ * d_r_d_x), x, jacobians[0]);
  }
  return true;
}

PointTestFactor::PointTestFactor(
    const Eigen::Vector3d& z, const Eigen::Matrix<double, Eigen::Dynamic, 3>& W)
    : z_(z), W_(W) {
  set_num_residuals(static_cast<int>(W_.rows()));
  mutable_parameter_block_sizes()->push_back(7);
  mutable_parameter_block_sizes()->push_back(3);
}

bool PointTestFactor::Evaluate(double const* const* parameters,
                               double* residuals, double** jacobians) const {
  const double* x = parameters[0];
  const Eigen::Map<const Eigen::Vector3d> t(x), l(parameters[1]);
  const Eigen::Matrix3d R_T = RotationOf(x).toRotationMatrix().transpose();
  const Eigen::Vector3d l_b = R_T * (l - t);
  const int k = num_residuals();
  Eigen::Map<Eigen::VectorXd> residual(residuals, k);
  residual = W_ * (l_b - z_);
  if (jacobians == nullptr) return true;
  if (jacobians[0] != nullptr) {
    // (R Exp(a))^T (l - t) ~ l_b + [l_b]x a;  d/dt = -R^T.
    Eigen::Matrix<double, 3, 6> d_lb_d_x;
    d_lb_d_x << -R_T, Skew(l_b);
    using Out = Eigen::Matrix<double, Eigen::Dynamic, 7, Eigen::RowMajor>;
    Eigen::Map<Out>(jacobians[0], k, 7) =
        W_ * d_lb_d_x * PoseManifold::MinusJacobianAt(x);
  }
  if (jacobians[1] != nullptr) {
    using Out = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
    Eigen::Map<Out>(jacobians[1], k, 3) = W_ * R_T;
  }
  return true;
}

bool DifferenceTestFactor::Evaluate(double const* const* parameters,
                                    double* residuals,
                                    double** jacobians) const {
  const Eigen::Map<const Eigen::Vector3d> b_i(parameters[0]),
      b_j(parameters[1]);
  Eigen::Map<Eigen::Vector3d> residual(residuals);
  residual = W_ * (b_j - b_i - d_);
  using Out = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;
  if (jacobians != nullptr && jacobians[0] != nullptr) {
    Eigen::Map<Out> d_r_d_bi(jacobians[0]);
    d_r_d_bi = -W_;
  }
  if (jacobians != nullptr && jacobians[1] != nullptr) {
    Eigen::Map<Out> d_r_d_bj(jacobians[1]);
    d_r_d_bj = W_;
  }
  return true;
}

}  // namespace testing
}  // namespace vio
