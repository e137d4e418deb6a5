#include "estimator/triangulation.h"

#include <gtest/gtest.h>

#include <random>

#include "geometry/so3.h"

namespace vio {
namespace {

// A camera at p_w_c looking along world +x (camera z) with a small random
// rotation on top.
Eigen::Isometry3d Camera(const Eigen::Vector3d& p_w_c,
                         const Eigen::Vector3d& phi) {
  Eigen::Matrix3d R_w_c0;
  R_w_c0 << 0, 0, 1,  //
      -1, 0, 0,       //
      0, -1, 0;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = R_w_c0 * Exp(phi);
  T.translation() = p_w_c;
  return T;
}

TriangulationView See(const Eigen::Isometry3d& T_w_c,
                      const Eigen::Vector3d& p_w) {
  const Eigen::Vector3d p_c = T_w_c.inverse() * p_w;
  return {T_w_c, p_c.head<2>() / p_c.z()};
}

TEST(Triangulate, RecoversPointsExactlyFromNoiseFreeViews) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const TriangulationOptions options;
  for (int i = 0; i < 100; ++i) {
    const Eigen::Vector3d p_w(3.0 + 5.0 * (u(rng) + 1.0), 2.0 * u(rng),
                              2.0 * u(rng));
    std::vector<TriangulationView> views;
    for (int k = 0; k < 2 + i % 8; ++k) {
      views.push_back(
          See(Camera(Eigen::Vector3d(0.2 * u(rng), 0.5 * u(rng), 0.3 * u(rng)),
                     0.1 * Eigen::Vector3d(u(rng), u(rng), u(rng))),
              p_w));
    }
    Eigen::Vector3d p_est;
    double depth = 0.0;
    if (MaxRayAngleDeg(views) < options.min_parallax_deg) continue;
    ASSERT_EQ(Triangulate(views, options, &p_est, &depth),
              TriangulationStatus::kOk);
    EXPECT_LT((p_est - p_w).norm(), 1e-8 * p_w.norm());
    EXPECT_NEAR(depth, (views[0].T_w_c.inverse() * p_w).z(), 1e-8);
  }
}

TEST(Triangulate, NoisyStereoPairGivesDepthWithinExpectedError) {
  // 0.11 m baseline, focal 460 px, 0.5 px noise, point at 4 m: the depth error
  // is about z^2 / (f b) * sigma = 16 / 50.6 * 0.5 = 0.16 m (1 sigma).
  std::mt19937 rng(3);
  std::normal_distribution<double> n(0.0, 0.5 / 460.0);
  const Eigen::Vector3d p_w(4.0, 0.3, -0.2);
  const Eigen::Isometry3d left = Camera({0, 0, 0}, Eigen::Vector3d::Zero());
  const Eigen::Isometry3d right =
      Camera({0, -0.11, 0}, Eigen::Vector3d::Zero());
  double sum_sq = 0.0;
  for (int i = 0; i < 200; ++i) {
    std::vector<TriangulationView> views = {See(left, p_w), See(right, p_w)};
    for (auto& v : views) v.xy += Eigen::Vector2d(n(rng), n(rng));
    Eigen::Vector3d p_est;
    double depth = 0.0;
    ASSERT_EQ(Triangulate(views, TriangulationOptions(), &p_est, &depth),
              TriangulationStatus::kOk);
    sum_sq += (depth - 4.0) * (depth - 4.0);
  }
  EXPECT_LT(std::sqrt(sum_sq / 200), 0.25);
}

TEST(Triangulate, RejectsPureRotationAsLowParallax) {
  const Eigen::Vector3d p_w(5.0, 1.0, 0.5);
  const std::vector<TriangulationView> views = {
      See(Camera({0, 0, 0}, {0, 0, 0}), p_w),
      See(Camera({0, 0, 0}, {0.1, 0.05, 0}), p_w)};
  EXPECT_NEAR(MaxRayAngleDeg(views), 0.0, 1e-6);
  Eigen::Vector3d p_est;
  double depth = 0.0;
  EXPECT_EQ(Triangulate(views, TriangulationOptions(), &p_est, &depth),
            TriangulationStatus::kLowParallax);
}

TEST(Triangulate, RejectsBadDepthAndTooFewViews) {
  TriangulationOptions options;
  const Eigen::Isometry3d a = Camera({0, 0, 0}, {0, 0, 0});
  const Eigen::Isometry3d b = Camera({0, -0.5, 0}, {0, 0, 0});
  Eigen::Vector3d p_est;
  double depth = 0.0;
  // Too far for the anchor.
  const Eigen::Vector3d far_w(60.0, 0.0, 0.0);
  options.min_parallax_deg = 0.0;
  EXPECT_EQ(
      Triangulate({See(a, far_w), See(b, far_w)}, options, &p_est, &depth),
      TriangulationStatus::kBadDepth);
  // Closer than the minimum depth.
  const Eigen::Vector3d near_w(0.05, -0.25, 0.0);
  EXPECT_EQ(
      Triangulate({See(a, near_w), See(b, near_w)}, options, &p_est, &depth),
      TriangulationStatus::kBadDepth);
  EXPECT_EQ(Triangulate({See(a, far_w)}, options, &p_est, &depth),
            TriangulationStatus::kTooFewViews);
}

}  // namespace
}  // namespace vio
