#include "eval/metrics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "test/testing/trajectories.h"

namespace vio {
namespace {

constexpr double kDeg = M_PI / 180.0;

StampedPose Pose(int64_t t_ns, Eigen::Vector3d p, double yaw_rad = 0.0) {
  StampedPose pose;
  pose.t_ns = t_ns;
  pose.p_w_b = p;
  pose.q_w_b = Eigen::Quaterniond(testing::Yaw(yaw_rad));
  return pose;
}

TEST(ErrorStats, FollowEvosDefinitions) {
  const ErrorStats s = ComputeStats({3.0, 1.0, 4.0, 2.0});
  EXPECT_EQ(s.count, 4u);
  EXPECT_DOUBLE_EQ(s.rmse, std::sqrt((9.0 + 1 + 16 + 4) / 4));
  EXPECT_DOUBLE_EQ(s.mean, 2.5);
  EXPECT_DOUBLE_EQ(s.median, 2.5);           // mean of the two middle values
  EXPECT_DOUBLE_EQ(s.std, std::sqrt(1.25));  // population std (1/n)
  EXPECT_DOUBLE_EQ(s.min, 1.0);
  EXPECT_DOUBLE_EQ(s.max, 4.0);
  EXPECT_DOUBLE_EQ(ComputeStats({5.0, 1.0, 2.0}).median, 2.0);
  EXPECT_TRUE(std::isnan(ComputeStats({}).rmse));
}

TEST(Ate, MeasuresPositionAndRotationPerPose) {
  const Trajectory gt = {Pose(0, {0, 0, 0}), Pose(1, {1, 0, 0}),
                         Pose(2, {2, 0, 0})};
  const Trajectory est = {Pose(0, {0, 0, 0}), Pose(1, {1, 0.3, 0.4}, 10 * kDeg),
                          Pose(2, {2, 0, 0}, -20 * kDeg)};
  const AbsoluteTrajectoryError ate = ComputeAte(est, gt);
  ASSERT_EQ(ate.translation_m.size(), 3u);
  EXPECT_NEAR(ate.translation_m[1], 0.5, 1e-15);  // |(0, 0.3, 0.4)|
  EXPECT_NEAR(ate.rotation_deg[1], 10.0, 1e-12);
  EXPECT_NEAR(ate.rotation_deg[2], 20.0, 1e-12);
  EXPECT_NEAR(ate.translation.rmse, std::sqrt(0.25 / 3), 1e-15);
  EXPECT_THROW(ComputeAte(est, {gt[0]}), std::invalid_argument);
}

// Ground truth moves 1 m along x per pose without turning; the estimate
//   P0 = (0, I), P1 = (1.1, I), P2 = (2.0, Rz(10 deg)), P3 = (3.3, I).
// With E = (Q_i^-1 Q_j)^-1 (P_i^-1 P_j), by hand:
//   (0,1): P_rel = (I, 1.1 x), Q_rel = (I, x): E = (I, 0.1 x)
//          -> 0.1 m, 0 deg
//   (1,2): P_rel = (Rz10, 0.9 x):              E = (Rz10, -0.1 x)
//          -> 0.1 m, 10 deg
//   (2,3): P_rel = (Rz-10, Rz-10 * 1.3 x):     E = (Rz-10, (1.3 c - 1, -1.3 s))
//          with c = cos 10 deg, s = sin 10 deg
//          -> sqrt(2.69 - 2.6 c) = 0.35986086 m, 10 deg
TEST(Rpe, MatchesAHandComputedCase) {
  const Trajectory gt = {Pose(0, {0, 0, 0}), Pose(1, {1, 0, 0}),
                         Pose(2, {2, 0, 0}), Pose(3, {3, 0, 0})};
  const Trajectory est = {Pose(0, {0, 0, 0}), Pose(1, {1.1, 0, 0}),
                          Pose(2, {2.0, 0, 0}, 10 * kDeg),
                          Pose(3, {3.3, 0, 0})};
  const RelativePoseError rpe = ComputeRpe(est, gt, 1, RpeUnit::kFrames);
  ASSERT_EQ(rpe.pairs.size(), 3u);
  const double c = std::cos(10 * kDeg);
  const double expected_m[] = {0.1, 0.1, std::sqrt(2.69 - 2.6 * c)};
  const double expected_deg[] = {0.0, 10.0, 10.0};
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(rpe.translation_m[k], expected_m[k], 1e-12) << k;
    EXPECT_NEAR(rpe.rotation_deg[k], expected_deg[k], 1e-10) << k;
  }
  EXPECT_NEAR(expected_m[2], 0.35986086, 1e-8);
  // Two-frame pairs: (0, 2) only; E = (Rz10, 0) -> 0 m, 10 deg.
  const RelativePoseError two = ComputeRpe(est, gt, 2, RpeUnit::kFrames);
  ASSERT_EQ(two.pairs.size(), 1u);
  EXPECT_NEAR(two.translation_m[0], 0.0, 1e-12);
  EXPECT_NEAR(two.rotation_deg[0], 10.0, 1e-10);
}

TEST(Rpe, MetrePairsFollowEvosPathWalk) {
  // Steps along x (exact in binary): 0.5, 0.75, 0.25, 1.25, 0.5, 0.5,
  // 0.25 m. Walking with delta 1 m: 0.5, 1.25 -> mark 2 (reset); 0.25, 1.5
  // -> mark 4; 0.5, 1.0 -> mark 6; 0.25 -> none. Pairs (2, 4), (4, 6): the walk
  // starts at the first mark, not at pose 0, as evo's filter_pairs_by_path
  // does.
  const double xs[] = {0.0, 0.5, 1.25, 1.5, 2.75, 3.25, 3.75, 4.0};
  Trajectory est;
  for (int i = 0; i < 8; ++i) est.push_back(Pose(i, {xs[i], 0, 0}));
  const IndexPairs pairs = RpePairs(est, 1.0, RpeUnit::kMeters);
  ASSERT_EQ(pairs.size(), 2u);
  EXPECT_EQ(pairs[0], std::make_pair(size_t{2}, size_t{4}));
  EXPECT_EQ(pairs[1], std::make_pair(size_t{4}, size_t{6}));
  // Frames: 0, 3, 6 -> (0, 3), (3, 6).
  const IndexPairs frames = RpePairs(est, 3, RpeUnit::kFrames);
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_EQ(frames[1], std::make_pair(size_t{3}, size_t{6}));
  EXPECT_TRUE(RpePairs(est, 100.0, RpeUnit::kMeters).empty());
  EXPECT_EQ(ComputeRpe(est, est, 100.0, RpeUnit::kMeters).translation.count,
            0u);
}

TEST(Rpe, RejectsBadDeltas) {
  const Trajectory t = testing::Lissajous(5);
  EXPECT_THROW(RpePairs(t, 0.0, RpeUnit::kMeters), std::invalid_argument);
  EXPECT_THROW(RpePairs(t, -1.0, RpeUnit::kFrames), std::invalid_argument);
  EXPECT_THROW(RpePairs(t, 1.5, RpeUnit::kFrames), std::invalid_argument);
  EXPECT_THROW(
      RpePairs(t, std::numeric_limits<double>::quiet_NaN(), RpeUnit::kMeters),
      std::invalid_argument);
}

TEST(Rpe, IsBlindToARigidMotionOfTheEstimate) {
  // E only involves P_i^-1 P_j, which a left-multiplied SE(3) cancels from.
  std::mt19937 rng(9);
  const Trajectory gt = testing::Lissajous(200);
  const Trajectory est = testing::AddPositionNoise(gt, 0.01, rng);
  const testing::Similarity S{testing::RandomRotation(rng), {5, 6, 7}, 1.0};
  const RelativePoseError a = ComputeRpe(est, gt, 1.0, RpeUnit::kMeters);
  const RelativePoseError b =
      ComputeRpe(testing::Transform(S, est), gt, 1.0, RpeUnit::kMeters);
  ASSERT_GT(a.pairs.size(), 5u);
  EXPECT_EQ(a.pairs, b.pairs);
  EXPECT_NEAR(a.translation.rmse, b.translation.rmse, 1e-12);
  EXPECT_NEAR(a.rotation.rmse, b.rotation.rmse, 1e-9);
  EXPECT_GT(a.translation.rmse, 0.005);  // and it does see the noise
}

}  // namespace
}  // namespace vio
