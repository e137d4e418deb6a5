#ifndef VIO_GEOMETRY_SO3_H_
#define VIO_GEOMETRY_SO3_H_

// SO(3) helpers shared by every module. Rotations are Hamilton quaternions
// stored [x, y, z, w] (Eigen's coefficient order); rotation vectors are full
// angles (phi = theta * axis, not half angles).
//
// The project's one perturbation convention (DESIGN.md) is on the right:
//   R (+) dtheta = R * Exp(dtheta),   q (+) dtheta = q (x) Exp(dtheta).
//
// References: Forster et al., "On-Manifold Preintegration for Real-Time
// Visual-Inertial Odometry", T-RO 2017, eqs. (1)-(8) (Exp, Log, right
// Jacobian); Sola, "Quaternion kinematics for the error-state Kalman filter",
// 2017, sec. 3.

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace vio {

// Below this angle [rad] Exp, Log and the right Jacobians switch to their
// Taylor expansions (stated at each function).
constexpr double kSmallAngle = 1e-5;

// [v]x, so that Skew(a) * b == a.cross(b).
Eigen::Matrix3d Skew(const Eigen::Vector3d& v);

// Exp: rotation vector [rad] -> unit quaternion / rotation matrix.
Eigen::Quaterniond ExpQuaternion(const Eigen::Vector3d& phi);
Eigen::Matrix3d Exp(const Eigen::Vector3d& phi);

// Log: the rotation vector with angle in [0, pi]. The quaternion need not have
// w >= 0 (q and -q give the same result).
Eigen::Vector3d Log(const Eigen::Quaterniond& q);
Eigen::Vector3d Log(const Eigen::Matrix3d& R);

// Right Jacobian of SO(3): Exp(phi + d) ~= Exp(phi) * Exp(Jr(phi) * d).
//   Jr = I - (1 - cos t)/t^2 [phi]x + (t - sin t)/t^3 [phi]x^2,  t = |phi|.
Eigen::Matrix3d RightJacobian(const Eigen::Vector3d& phi);

// Its inverse: Log(Exp(phi) * Exp(d)) ~= phi + Jr^-1(phi) * d.
//   Jr^-1 = I + 1/2 [phi]x + (1/t^2 - (1 + cos t)/(2 t sin t)) [phi]x^2.
// Singular at t = 2*pi; finite for every rotation vector returned by Log.
Eigen::Matrix3d RightJacobianInverse(const Eigen::Vector3d& phi);

// Quaternion product as a matrix on the [x, y, z, w] coefficients:
//   (q (x) p).coeffs() == QuaternionLeftMatrix(q) * p.coeffs()
//                      == QuaternionRightMatrix(p) * q.coeffs().
Eigen::Matrix4d QuaternionLeftMatrix(const Eigen::Quaterniond& q);
Eigen::Matrix4d QuaternionRightMatrix(const Eigen::Quaterniond& p);

}  // namespace vio

#endif  // VIO_GEOMETRY_SO3_H_
