#include "geometry/so3.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace vio {
namespace {

// Angles that probe every branch: zero, below and above kSmallAngle, large,
// and close to pi.
const double kAngles[] = {
    0.0, 1e-12, 1e-8, 0.5 * kSmallAngle, 2.0 * kSmallAngle, 1e-3,
    0.3, 1.5,   3.0,  M_PI - 1e-6};

Eigen::Vector3d RandomAxis(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  return Eigen::Vector3d(n(rng), n(rng), n(rng)).normalized();
}

TEST(So3, SkewIsCrossProduct) {
  const Eigen::Vector3d a(1, -2, 3), b(0.5, 4, -1);
  EXPECT_TRUE((Skew(a) * b).isApprox(a.cross(b)));
}

TEST(So3, ExpMatchesAngleAxis) {
  std::mt19937 rng(42);
  for (double t : kAngles) {
    const Eigen::Vector3d axis = RandomAxis(rng);
    const Eigen::Matrix3d expected =
        Eigen::AngleAxisd(t, axis).toRotationMatrix();
    EXPECT_TRUE(Exp(t * axis).isApprox(expected, 1e-12)) << "angle " << t;
  }
}

TEST(So3, LogInvertsExp) {
  std::mt19937 rng(42);
  for (double t : kAngles) {
    const Eigen::Vector3d phi = t * RandomAxis(rng);
    EXPECT_LT((Log(ExpQuaternion(phi)) - phi).norm(), 1e-9 * (1.0 + t))
        << "angle " << t;
    // -q is the same rotation.
    const Eigen::Quaterniond neg(-ExpQuaternion(phi).coeffs());
    EXPECT_LT((Log(neg) - phi).norm(), 1e-9 * (1.0 + t)) << "angle " << t;
  }
}

// Jr(phi) d ~= Log(Exp(phi)^-1 Exp(phi + d)) for small d, by central
// differences; and Jr^-1 is its inverse.
TEST(So3, RightJacobianMatchesNumericDiff) {
  std::mt19937 rng(7);
  const double h = 1e-6;
  for (double t : kAngles) {
    const Eigen::Vector3d phi = t * RandomAxis(rng);
    Eigen::Matrix3d numeric;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d d = h * Eigen::Vector3d::Unit(k);
      const Eigen::Quaterniond q0 = ExpQuaternion(phi).conjugate();
      numeric.col(k) = (Log(q0 * ExpQuaternion(phi + d)) -
                        Log(q0 * ExpQuaternion(phi - d))) /
                       (2.0 * h);
    }
    EXPECT_LT((RightJacobian(phi) - numeric).cwiseAbs().maxCoeff(), 1e-8)
        << "angle " << t;
    EXPECT_LT((RightJacobianInverse(phi) * RightJacobian(phi) -
               Eigen::Matrix3d::Identity())
                  .cwiseAbs()
                  .maxCoeff(),
              1e-9)
        << "angle " << t;
  }
}

TEST(So3, QuaternionProductMatrices) {
  std::mt19937 rng(3);
  const Eigen::Quaterniond q = ExpQuaternion(0.7 * RandomAxis(rng));
  const Eigen::Quaterniond p = ExpQuaternion(2.1 * RandomAxis(rng));
  const Eigen::Vector4d qp = (q * p).coeffs();
  EXPECT_TRUE((QuaternionLeftMatrix(q) * p.coeffs()).isApprox(qp, 1e-14));
  EXPECT_TRUE((QuaternionRightMatrix(p) * q.coeffs()).isApprox(qp, 1e-14));
}

}  // namespace
}  // namespace vio
