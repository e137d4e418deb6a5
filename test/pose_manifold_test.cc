#include "factors/pose_manifold.h"

#include <ceres/manifold_test_utils.h>
#include <gtest/gtest.h>

#include <random>

#include "geometry/so3.h"

namespace vio {
namespace {

Eigen::Matrix<double, 7, 1> RandomPose(std::mt19937& rng, double angle) {
  std::normal_distribution<double> n(0.0, 1.0);
  const Eigen::Vector3d axis =
      Eigen::Vector3d(n(rng), n(rng), n(rng)).normalized();
  Eigen::Matrix<double, 7, 1> x;
  x.head<3>() = Eigen::Vector3d(n(rng), n(rng), n(rng));
  x.tail<4>() = ExpQuaternion(angle * axis).coeffs();
  return x;
}

TEST(PoseManifold, InvariantsHold) {
  // The Ceres macro names its helpers (Vector, XPlusZeroIsXAt, ...)
  // unqualified.
  using namespace ceres;  // NOLINT(build/namespaces)
  std::mt19937 rng(42);
  const PoseManifold manifold;
  std::normal_distribution<double> n(0.0, 1.0);
  for (double angle : {0.0, 1e-8, 0.4, 2.0, M_PI - 1e-4}) {
    for (int i = 0; i < 5; ++i) {
      const Eigen::VectorXd x = RandomPose(rng, angle);
      Eigen::VectorXd y = RandomPose(rng, 1.0);
      // q and -q are one rotation; Plus(x, Minus(y, x)) returns the
      // representative in x's hemisphere, so compare with that one.
      if (x.tail<4>().dot(y.tail<4>()) < 0.0) y.tail<4>() *= -1.0;
      Eigen::VectorXd delta(6);
      for (int k = 0; k < 6; ++k) delta[k] = 0.3 * n(rng);
      EXPECT_THAT_MANIFOLD_INVARIANTS_HOLD(manifold, x, delta, y, 1e-9);
    }
  }
}

TEST(PoseManifold, PlusIsRightPerturbation) {
  std::mt19937 rng(1);
  const Eigen::Matrix<double, 7, 1> x = RandomPose(rng, 1.2);
  Eigen::Matrix<double, 6, 1> delta;
  delta << 0.1, -0.2, 0.3, 0.05, -0.02, 0.04;
  Eigen::Matrix<double, 7, 1> y;
  PoseManifold().Plus(x.data(), delta.data(), y.data());
  const Eigen::Quaterniond q(Eigen::Vector4d(x.tail<4>()));
  const Eigen::Quaterniond expected = q * ExpQuaternion(delta.tail<3>());
  EXPECT_TRUE(y.head<3>().isApprox(x.head<3>() + delta.head<3>()));
  EXPECT_TRUE(y.tail<4>().isApprox(expected.coeffs(), 1e-14));
}

TEST(PoseManifold, MinusJacobianLeftInvertsPlusJacobian) {
  std::mt19937 rng(2);
  for (int i = 0; i < 20; ++i) {
    const Eigen::Matrix<double, 7, 1> x = RandomPose(rng, 0.2 * i);
    const Eigen::Matrix<double, 6, 6> product =
        PoseManifold::MinusJacobianAt(x.data()) *
        PoseManifold::PlusJacobianAt(x.data());
    EXPECT_TRUE(
        product.isApprox(Eigen::Matrix<double, 6, 6>::Identity(), 1e-14));
  }
}

}  // namespace
}  // namespace vio
