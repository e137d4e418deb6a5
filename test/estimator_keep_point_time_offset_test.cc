// End to end: the camera-IMU time offset t_d estimated with the shipped
// stereo landmark keys (config/stereo.yaml: reanchored_tracks
// keep_point_fej, world points on top of max_landmarks 60, at most 50), whose
// world points are reprojected by TimedWorldPointReprojectionFactor
// (factors/timed_world_point_factor.h). Same sequence as
// estimator_calibration_test's stereo t_d case (the aggressive preset's
// motion, stereo, a true +5 ms offset, 12 s): t_d is found within that
// case's 1 ms, and the trajectory is no worse than with reuse by more than
// the margin below.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>

#include "estimator/estimator.h"
#include "test/testing/sim_replay.h"

namespace vio {
namespace {

using testing::SimReplay;

constexpr double kTruth = 0.005;  // [s]

// The calibration test's aggressive motion (testing::AggressiveSimulation),
// stereo, this seed.
Simulation AggressiveStereo(uint32_t seed) {
  SimulatorOptions o = testing::AggressiveSimulation(12.0, true, kTruth);
  o.seed = seed;
  return Simulate(o);
}

// t_d estimated from 0 with config/stereo.yaml's landmark keys, the tracks
// of a leaving keyframe kept as `mode`.
SimReplay Run(const Simulation& sim, ReanchoredTracks mode) {
  EstimatorOptions o = testing::OptionsFor(sim.options);
  o.estimate_time_offset = true;
  o.landmarks.max_landmarks = 60;
  o.landmarks.reanchored_tracks = mode;
  o.landmarks.world_points_in_max_landmarks = false;
  o.landmarks.max_world_points = 50;
  const SimReplay r = testing::ReplaySimulation(sim, o);
  std::printf(
      "seed %u, %s: t_d %.5f s (truth %.4f), ATE %.4f m, resets %lld, "
      "%lld marginalisations (%lld failed), at most %lld world points\n",
      sim.options.seed, ReanchoredTracksName(mode), r.time_offset_s, kTruth,
      r.ate_rmse_m, static_cast<long long>(r.summary.resets),
      static_cast<long long>(r.summary.marginalizations),
      static_cast<long long>(r.summary.marginalization_failures),
      static_cast<long long>(r.summary.most_world_points));
  return r;
}

// The ATE margin over reuse with t_d estimated, chosen on seed 1 and checked
// on seed 2 (held out). Measured: seed 1 keep_point_fej 4.90 ms, ATE
// 0.0135 m against reuse's 4.88 ms, 0.0171 m; seed 2 4.96 ms, 0.0120 m
// against 4.78 ms, 0.0143 m. 10 % is estimator_calibration_test's margin
// over t_d held at the truth. Broken on purpose, the world points' velocity
// dropped gives 0.062 / 0.087 m, the t_d Jacobian's sign flipped -20 ms (the
// bound), the folded factors untimed 3.9 / 4.2 ms.
constexpr double kAteMargin = 1.10;

void ExpectTimeOffsetFoundWithWorldPoints(uint32_t seed) {
  const Simulation sim = AggressiveStereo(seed);
  const SimReplay fej = Run(sim, ReanchoredTracks::kKeepPointFirstEstimate);
  const SimReplay reuse = Run(sim, ReanchoredTracks::kReuse);
  // The world points were there, on the t_d block, all run long.
  EXPECT_GT(fej.summary.most_world_points, 0);
  EXPECT_EQ(fej.summary.marginalization_failures, 0);
  EXPECT_EQ(fej.summary.resets, 0);
  EXPECT_NEAR(fej.time_offset_s, kTruth, 1e-3);
  EXPECT_LT(fej.ate_rmse_m, kAteMargin * reuse.ate_rmse_m);
}

TEST(EstimatorKeepPointTimeOffset, StereoFindsTheOffsetSeed1) {
  ExpectTimeOffsetFoundWithWorldPoints(1);
}

// Held out: the margin was not chosen on it.
TEST(EstimatorKeepPointTimeOffset, StereoFindsTheOffsetSeed2) {
  ExpectTimeOffsetFoundWithWorldPoints(2);
}

}  // namespace
}  // namespace vio
