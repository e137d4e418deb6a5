#include "geometry/so3.h"

#include <cmath>

namespace vio {

Eigen::Matrix3d Skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0.0, -v.z(), v.y(),  //
      v.z(), 0.0, -v.x(),   //
      -v.y(), v.x(), 0.0;
  return m;
}

Eigen::Quaterniond ExpQuaternion(const Eigen::Vector3d& phi) {
  // q = [sin(t/2)/t * phi, cos(t/2)]. Below kSmallAngle the coefficients are
  // their second-order Taylor series: sin(t/2)/t ~ 1/2 - t^2/48,
  // cos(t/2) ~ 1 - t^2/8 (error O(t^4) < 1e-20).
  const double t2 = phi.squaredNorm();
  double k, w;
  if (t2 < kSmallAngle * kSmallAngle) {
    k = 0.5 - t2 / 48.0;
    w = 1.0 - t2 / 8.0;
  } else {
    const double t = std::sqrt(t2);
    k = std::sin(0.5 * t) / t;
    w = std::cos(0.5 * t);
  }
  Eigen::Quaterniond q(w, k * phi.x(), k * phi.y(), k * phi.z());
  q.normalize();
  return q;
}

Eigen::Matrix3d Exp(const Eigen::Vector3d& phi) {
  return ExpQuaternion(phi).toRotationMatrix();
}

Eigen::Vector3d Log(const Eigen::Quaterniond& q_in) {
  // Take the representative with w >= 0 so the angle is in [0, pi].
  const Eigen::Quaterniond q =
      q_in.w() < 0.0 ? Eigen::Quaterniond(-q_in.coeffs()) : q_in;
  const Eigen::Vector3d v = q.vec();
  const double n = v.norm();
  const double w = q.w();
  if (n < 0.5 * kSmallAngle) {
    // t = 2 atan(n / w); t / n ~ (2 / w) * (1 - n^2 / (3 w^2)) to second order.
    return (2.0 / w) * (1.0 - n * n / (3.0 * w * w)) * v;
  }
  return (2.0 * std::atan2(n, w) / n) * v;
}

Eigen::Vector3d Log(const Eigen::Matrix3d& R) {
  return Log(Eigen::Quaterniond(R));
}

Eigen::Matrix3d RightJacobian(const Eigen::Vector3d& phi) {
  const double t2 = phi.squaredNorm();
  const Eigen::Matrix3d W = Skew(phi);
  if (t2 < kSmallAngle * kSmallAngle) {
    // Second-order Taylor series of the closed form.
    return Eigen::Matrix3d::Identity() - 0.5 * W + (1.0 / 6.0) * W * W;
  }
  const double t = std::sqrt(t2);
  return Eigen::Matrix3d::Identity() - (1.0 - std::cos(t)) / t2 * W +
         (t - std::sin(t)) / (t2 * t) * W * W;
}

Eigen::Matrix3d RightJacobianInverse(const Eigen::Vector3d& phi) {
  const double t2 = phi.squaredNorm();
  const Eigen::Matrix3d W = Skew(phi);
  if (t2 < kSmallAngle * kSmallAngle) {
    return Eigen::Matrix3d::Identity() + 0.5 * W + (1.0 / 12.0) * W * W;
  }
  const double t = std::sqrt(t2);
  return Eigen::Matrix3d::Identity() + 0.5 * W +
         (1.0 / t2 - (1.0 + std::cos(t)) / (2.0 * t * std::sin(t))) * W * W;
}

Eigen::Matrix4d QuaternionLeftMatrix(const Eigen::Quaterniond& q) {
  // q (x) p with q = (v, w), p = (u, s): vec = w u + s v + v x u,
  // scalar = w s - v.u.
  Eigen::Matrix4d L;
  L.topLeftCorner<3, 3>() = q.w() * Eigen::Matrix3d::Identity() + Skew(q.vec());
  L.topRightCorner<3, 1>() = q.vec();
  L.bottomLeftCorner<1, 3>() = -q.vec().transpose();
  L(3, 3) = q.w();
  return L;
}

Eigen::Matrix4d QuaternionRightMatrix(const Eigen::Quaterniond& p) {
  // Same product read as a function of q: vec = s v + w u - u x v.
  Eigen::Matrix4d R;
  R.topLeftCorner<3, 3>() = p.w() * Eigen::Matrix3d::Identity() - Skew(p.vec());
  R.topRightCorner<3, 1>() = p.vec();
  R.bottomLeftCorner<1, 3>() = -p.vec().transpose();
  R(3, 3) = p.w();
  return R;
}

}  // namespace vio
