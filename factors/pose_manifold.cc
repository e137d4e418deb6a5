#include "factors/pose_manifold.h"

#include <Eigen/Geometry>

#include "geometry/so3.h"

namespace vio {
namespace {

Eigen::Quaterniond Rotation(const double* x) {
  return Eigen::Quaterniond(Eigen::Map<const Eigen::Vector4d>(x + 3));
}

}  // namespace

bool PoseManifold::Plus(const double* x, const double* delta,
                        double* x_plus_delta) const {
  Eigen::Map<const Eigen::Vector3d> t(x);
  Eigen::Map<const Eigen::Vector3d> dt(delta);
  Eigen::Map<const Eigen::Vector3d> dtheta(delta + 3);
  Eigen::Map<Eigen::Vector3d> t_out(x_plus_delta);
  Eigen::Map<Eigen::Vector4d> q_out(x_plus_delta + 3);
  t_out = t + dt;
  Eigen::Quaterniond q = Rotation(x) * ExpQuaternion(dtheta);
  q.normalize();
  q_out = q.coeffs();
  return true;
}

PosePlusJacobian PoseManifold::PlusJacobianAt(const double* x) {
  // d (q (x) Exp(d)) / d d at d = 0: Exp(d) ~ [d / 2, 1], so the derivative is
  // half of the first three columns of the left product matrix of q.
  PosePlusJacobian J = PosePlusJacobian::Zero();
  J.topLeftCorner<3, 3>().setIdentity();
  J.bottomRightCorner<4, 3>() =
      0.5 * QuaternionLeftMatrix(Rotation(x)).leftCols<3>();
  return J;
}

bool PoseManifold::PlusJacobian(const double* x, double* jacobian) const {
  Eigen::Map<PosePlusJacobian> out(jacobian);
  out = PlusJacobianAt(x);
  return true;
}

bool PoseManifold::Minus(const double* y, const double* x,
                         double* y_minus_x) const {
  Eigen::Map<Eigen::Vector3d> dt(y_minus_x);
  Eigen::Map<Eigen::Vector3d> dtheta(y_minus_x + 3);
  dt = Eigen::Map<const Eigen::Vector3d>(y) -
       Eigen::Map<const Eigen::Vector3d>(x);
  dtheta = Log(Rotation(x).conjugate() * Rotation(y));
  return true;
}

PoseMinusJacobian PoseManifold::MinusJacobianAt(const double* x) {
  // d Log(q_x^-1 (x) q_y) / d q_y at q_y = q_x: near identity Log(p) ~ 2 p.vec,
  // so the derivative is twice the first three rows of L(q_x^-1).
  // With L(q)[:, :3] = [w I + [v]x; -v^T] and L(q^-1)[:3, :] = [w I - [v]x,
  // -v], their product is (w^2 + |v|^2) I = I: MinusJacobian * PlusJacobian =
  // I.
  PoseMinusJacobian J = PoseMinusJacobian::Zero();
  J.topLeftCorner<3, 3>().setIdentity();
  J.bottomRightCorner<3, 4>() =
      2.0 * QuaternionLeftMatrix(Rotation(x).conjugate()).topRows<3>();
  return J;
}

bool PoseManifold::MinusJacobian(const double* x, double* jacobian) const {
  Eigen::Map<PoseMinusJacobian> out(jacobian);
  out = MinusJacobianAt(x);
  return true;
}

}  // namespace vio
