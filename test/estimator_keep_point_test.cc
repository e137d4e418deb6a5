// landmarks.reanchored_tracks keep_point / keep_point_fej over a whole run
// (estimator/window_problem_points.cc, estimator/estimator_points.cc): the
// world points enter and leave the prior without a failed marginalisation,
// and the run tracks as well as reuse does; reuse_after_moving_start_s
// holds the conversion back after a start in motion only.

#include <gtest/gtest.h>

#include <cstdio>

#include "estimator/estimator.h"
#include "test/testing/sim_replay.h"

namespace vio {
namespace {

using testing::ReplaySimulation;
using testing::SimReplay;

SimReplay ReplayWith(bool stereo, ReanchoredTracks mode,
                     double outlier_fraction = 0.0,
                     bool points_in_max_landmarks = true,
                     int max_world_points = 0) {
  SimulatorOptions sim = testing::ShortSimulation(12.0, stereo);
  sim.camera.outlier_fraction = outlier_fraction;
  EstimatorOptions options = testing::OptionsFor(sim);
  options.landmarks.reanchored_tracks = mode;
  options.landmarks.world_points_in_max_landmarks = points_in_max_landmarks;
  options.landmarks.max_world_points = max_world_points;
  const SimReplay r = ReplaySimulation(Simulate(sim), options);
  std::printf(
      "%s %s: ATE %.6f m, %lld marginalisations (%lld failed), "
      "%lld releases, at most %.0f landmarks a step, %lld world points "
      "capped, at most %lld held\n",
      stereo ? "stereo" : "mono", ReanchoredTracksName(mode), r.ate_rmse_m,
      static_cast<long long>(r.summary.marginalizations),
      static_cast<long long>(r.summary.marginalization_failures),
      static_cast<long long>(r.summary.points_released),
      r.summary.landmarks_per_step.Quantile(1.0),
      static_cast<long long>(r.summary.points_capped),
      static_cast<long long>(r.summary.most_world_points));
  return r;
}

TEST(EstimatorKeepPoint, MonoTracksWithEveryMarginalizationSucceeding) {
  const SimReplay fej =
      ReplayWith(false, ReanchoredTracks::kKeepPointFirstEstimate);
  EXPECT_EQ(fej.summary.resets, 0);
  EXPECT_GT(fej.summary.marginalizations, 20);
  EXPECT_EQ(fej.summary.marginalization_failures, 0);
  // reuse measures 0.031 m here (estimator_test); the bound is reuse's.
  EXPECT_LT(fej.ate_rmse_m, 0.06);
}

TEST(EstimatorKeepPoint, StereoTracksWithEveryMarginalizationSucceeding) {
  const SimReplay fej =
      ReplayWith(true, ReanchoredTracks::kKeepPointFirstEstimate);
  EXPECT_EQ(fej.summary.resets, 0);
  EXPECT_GT(fej.summary.marginalizations, 20);
  EXPECT_EQ(fej.summary.marginalization_failures, 0);
  EXPECT_LT(fej.ate_rmse_m, 0.02);
}

TEST(EstimatorKeepPoint, StereoPointsOnTopOfMaxLandmarks) {
  // world_points_in_max_landmarks false: the world points come on top of
  // max_landmarks inverse-depth landmarks, so a step holds more than it.
  const SimReplay fej =
      ReplayWith(true, ReanchoredTracks::kKeepPointFirstEstimate, 0.0, false);
  const int max_landmarks =
      testing::OptionsFor(testing::ShortSimulation(12.0, true))
          .landmarks.max_landmarks;
  EXPECT_GT(fej.summary.landmarks_per_step.Quantile(1.0), max_landmarks);
  EXPECT_EQ(fej.summary.resets, 0);
  EXPECT_EQ(fej.summary.marginalization_failures, 0);
  EXPECT_LT(fej.ate_rmse_m, 0.02);
}

TEST(EstimatorKeepPoint, MonoOutliersReleasePointsWithoutFailure) {
  // Outliers removed from world points leave orphans: the release path
  // (Estimator::ReleaseOrphanPoints, estimator/point_release.h) runs.
  const SimReplay fej =
      ReplayWith(false, ReanchoredTracks::kKeepPointFirstEstimate, 0.1);
  EXPECT_GT(fej.summary.points_released, 0);
  EXPECT_EQ(fej.summary.resets, 0);
  EXPECT_EQ(fej.summary.marginalization_failures, 0);
  EXPECT_LT(fej.ate_rmse_m, 0.06);
}

TEST(EstimatorKeepPoint, MonoWorldPointsWithinTheirBound) {
  // max_world_points 15 with the points on top of max_landmarks (the
  // variant of docs/recorded_flights.md): never more than 15 world points
  // after a marginalisation, the excess marginalised (points_capped), every
  // marginalisation succeeding, the run as accurate as reuse's bound.
  const SimReplay capped =
      ReplayWith(false, ReanchoredTracks::kKeepPointFirstEstimate, 0.0, false,
                 15);
  EXPECT_GT(capped.summary.points_capped, 0);
  EXPECT_LE(capped.summary.most_world_points, 15);
  EXPECT_GT(capped.summary.most_world_points, 0);
  EXPECT_EQ(capped.summary.resets, 0);
  EXPECT_GT(capped.summary.marginalizations, 20);
  EXPECT_EQ(capped.summary.marginalization_failures, 0);
  EXPECT_LT(capped.ate_rmse_m, 0.06);
}

// keep_point_fej with reuse_after_moving_start_s = reuse_s on a 12 s mono
// run, at rest for its first 2 s (a static start) or in motion from its
// first sample.
SimReplay ReplayStart(bool in_motion, double reuse_s) {
  SimulatorOptions sim = testing::ShortSimulation(12.0, false);
  if (in_motion) {
    sim.motion.still_duration_s = 0.0;
    sim.motion.blend_duration_s = 0.0;
  }
  EstimatorOptions options = testing::OptionsFor(sim);
  options.landmarks.reanchored_tracks =
      ReanchoredTracks::kKeepPointFirstEstimate;
  options.landmarks.reuse_after_moving_start_s = reuse_s;
  const SimReplay r = ReplaySimulation(Simulate(sim), options);
  std::printf("%s start, reuse for %.0f s: %s, ATE %.6f m, at most %lld "
              "world points, %lld marginalisations\n",
              in_motion ? "in-motion" : "static", reuse_s,
              r.summary.starts.empty()
                  ? "no start"
                  : InitMethodName(r.summary.starts.front().method),
              r.ate_rmse_m, static_cast<long long>(r.summary.most_world_points),
              static_cast<long long>(r.summary.marginalizations));
  return r;
}

TEST(EstimatorKeepPoint, ReuseAfterMovingStartOnlyAfterAStartInMotion) {
  // Longer than the run: after a start in motion no track ever becomes a
  // world point; after a static start the key does nothing.
  const SimReplay moving = ReplayStart(true, 100.0);
  ASSERT_FALSE(moving.summary.starts.empty());
  EXPECT_NE(moving.summary.starts.front().method, InitMethod::kStatic);
  EXPECT_GT(moving.summary.marginalizations, 20);
  EXPECT_EQ(moving.summary.most_world_points, 0);
  EXPECT_EQ(moving.summary.resets, 0);
  const SimReplay moving_now = ReplayStart(true, 0.0);
  EXPECT_GT(moving_now.summary.most_world_points, 0);
  const SimReplay still = ReplayStart(false, 100.0);
  ASSERT_FALSE(still.summary.starts.empty());
  EXPECT_EQ(still.summary.starts.front().method, InitMethod::kStatic);
  EXPECT_GT(still.summary.most_world_points, 0);
  // Shorter than the run: world points once the span has passed.
  const SimReplay moving_4s = ReplayStart(true, 4.0);
  EXPECT_GT(moving_4s.summary.most_world_points, 0);
  EXPECT_EQ(moving_4s.summary.marginalization_failures, 0);
  EXPECT_EQ(moving_4s.summary.resets, 0);
}

}  // namespace
}  // namespace vio
