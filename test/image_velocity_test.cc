#include "estimator/image_velocity.h"

#include <gtest/gtest.h>

#include <limits>
#include <random>

#include "geometry/so3.h"

namespace vio {
namespace {

// xy of the world point p_w seen from the body at T_w_b through T_b_c.
Eigen::Vector2d Project(const Eigen::Vector3d& p_w,
                        const Eigen::Isometry3d& T_w_b,
                        const Eigen::Isometry3d& T_b_c) {
  const Eigen::Vector3d p_c = (T_w_b * T_b_c).inverse() * p_w;
  return p_c.head<2>() / p_c.z();
}

// The predicted velocity equals the central difference of the projection
// along the motion T_w_b(t) = (p + v_w t, R Exp(w_b t)), for random states,
// extrinsics and points in front of the camera.
TEST(ImageVelocity, MatchesTheDerivativeOfTheProjection) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const auto random3 = [&]() {
    return Eigen::Vector3d(u(rng), u(rng), u(rng));
  };
  for (int trial = 0; trial < 20; ++trial) {
    Eigen::Isometry3d T_w_b = Eigen::Isometry3d::Identity();
    T_w_b.linear() = Exp(2.0 * random3());
    T_w_b.translation() = 3.0 * random3();
    Eigen::Isometry3d T_b_c = Eigen::Isometry3d::Identity();
    T_b_c.linear() = Exp(0.5 * random3());
    T_b_c.translation() = 0.1 * random3();
    const Eigen::Vector3d v_w = 2.0 * random3();
    const Eigen::Vector3d w_b = 1.5 * random3();
    const Eigen::Vector3d p_c(u(rng), u(rng), 2.0 + 3.0 * (u(rng) + 1.0));
    const Eigen::Vector3d p_w = T_w_b * T_b_c * p_c;

    const double h = 1e-6;  // [s]
    const auto at = [&](double t) {
      Eigen::Isometry3d T = T_w_b;
      T.translation() += v_w * t;
      T.linear() = T_w_b.linear() * Exp(w_b * t);
      return Project(p_w, T, T_b_c);
    };
    const Eigen::Vector2d numeric = (at(h) - at(-h)) / (2.0 * h);
    const Eigen::Vector2d predicted =
        PredictedImageVelocity(p_c, T_w_b, v_w, w_b, T_b_c);
    EXPECT_LT((predicted - numeric).norm(), 1e-6 * (1.0 + numeric.norm()))
        << "trial " << trial << ": " << predicted.transpose() << " vs "
        << numeric.transpose();
  }
}

TEST(ImageVelocity, IsZeroForAPointBehindTheCameraOrAtInfinity) {
  const double inf = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& p_c :
       {Eigen::Vector3d(0.1, 0.2, -1.0), Eigen::Vector3d(inf, inf, inf),
        Eigen::Vector3d(Eigen::Vector3d(0.1, 0.2, 1.0) / 0.0)}) {
    const Eigen::Vector2d v = PredictedImageVelocity(
        p_c, Eigen::Isometry3d::Identity(), Eigen::Vector3d(1.0, 0.0, 0.0),
        Eigen::Vector3d(0.0, 0.5, 0.0), Eigen::Isometry3d::Identity());
    EXPECT_EQ(v, Eigen::Vector2d::Zero()) << p_c.transpose();
  }
}

}  // namespace
}  // namespace vio
