// End to end: the estimator's online calibration (time offset t_d and the
// camera extrinsic T_b_c) converges to the simulator's truth on a short,
// well-excited sequence generated here.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "estimator/estimator.h"
#include "estimator/sequence_runner.h"
#include "geometry/so3.h"
#include "test/testing/sim_replay.h"

namespace vio {
namespace {

using testing::SimReplay;

using testing::AggressiveSimulation;

double RotationDeg(const Eigen::Matrix3d& R) {
  return Log(R).norm() * 180.0 / M_PI;
}

// With t_d estimated from 0, the true +5 ms is found within 1 ms under the
// simulator's default noise (1 px), and the trajectory is as good as with t_d
// held at the truth. (With the tracker's image velocity the estimate hits
// the 20 ms bound here; with the lagged one the 40 s preset gave -5.6 ms.)
// Measured with reuse: 4.97 ms, ATE 0.0274 m against 0.0289 m at the
// truth; -5 ms and +10 ms gave -4.86 ms and 9.96 ms. With the built-in
// defaults since the mono switch (world points): 5.01 ms, ATE 0.0157 m
// against 0.0162 m.
TEST(EstimatorCalibration, TimeOffsetConvergesToTheTruthUnderNoise) {
  const double truth = 0.005;  // [s]
  const Simulation sim = Simulate(AggressiveSimulation(12.0, false, truth));
  // The built-in defaults: world points (keep_point_fej) take the time
  // shift too (factors/timed_world_point_factor.h); the stereo case below
  // runs reuse, estimator_keep_point_time_offset_test stereo with world
  // points.
  EstimatorOptions estimated = testing::OptionsFor(sim.options);
  estimated.estimate_time_offset = true;
  EstimatorOptions fixed = estimated;
  fixed.estimate_time_offset = false;
  fixed.initial_time_offset_s = truth;
  const SimReplay r = testing::ReplaySimulation(sim, estimated);
  const SimReplay at_truth = testing::ReplaySimulation(sim, fixed);
  std::printf(
      "t_d truth %.4f s: estimated %.5f s, ATE %.4f m (t_d fixed at the "
      "truth: %.4f m), resets %lld\n",
      truth, r.time_offset_s, r.ate_rmse_m, at_truth.ate_rmse_m,
      static_cast<long long>(r.summary.resets));
  EXPECT_EQ(r.summary.resets, 0);
  EXPECT_NEAR(r.time_offset_s, truth, 1e-3);
  EXPECT_LT(r.ate_rmse_m, 1.1 * at_truth.ate_rmse_m);
}

// Stereo with t_d estimated (issue 11's review), landmarks re-anchored
// (reuse): camera 0's and camera 1's factors between frames are timed
// (shifted along each camera's predicted image velocity), the same-frame
// stereo factors need no shift. The combination must find the truth and
// track as well as with t_d held at the truth. (With world points, the
// shipped stereo files' keep_point_fej: estimator_keep_point_time_offset_test.)
TEST(EstimatorCalibration, TimeOffsetConvergesWithStereo) {
  const double truth = 0.005;  // [s]
  const Simulation sim = Simulate(AggressiveSimulation(12.0, true, truth));
  EstimatorOptions estimated = testing::OptionsFor(sim.options);
  estimated.landmarks.reanchored_tracks = ReanchoredTracks::kReuse;
  estimated.estimate_time_offset = true;
  estimated.landmarks.max_landmarks = 60;  // as config/stereo.yaml
  EstimatorOptions fixed = estimated;
  fixed.estimate_time_offset = false;
  fixed.initial_time_offset_s = truth;
  const SimReplay r = testing::ReplaySimulation(sim, estimated);
  const SimReplay at_truth = testing::ReplaySimulation(sim, fixed);
  std::printf(
      "stereo, t_d truth %.4f s: estimated %.5f s, ATE %.4f m (t_d fixed at "
      "the truth: %.4f m), resets %lld\n",
      truth, r.time_offset_s, r.ate_rmse_m, at_truth.ate_rmse_m,
      static_cast<long long>(r.summary.resets));
  EXPECT_EQ(r.summary.resets, 0);
  EXPECT_NEAR(r.time_offset_s, truth, 1e-3);
  EXPECT_LT(r.ate_rmse_m, 1.1 * at_truth.ate_rmse_m);
}

// T_b_c started 4 deg and 3.9 cm off the truth comes back to it: rotation
// to hundredths of a degree, translation (less observable) to millimetres.
// The run is 20 s: the translation converges slowly (about 39 mm at 2 s,
// 30 mm at 4 s, 20 mm at 6 s) and at 12 s is still falling, so its value
// at the end of a 12 s run is a snapshot of the transient (seed 1 with the
// built-in defaults, keep_point_fej: 9.2 to 10.4 mm over its last 2 s; over
// seeds 1-10 at 12 s mean 5.7 mm, reuse 5.1 mm). At 20 s, seeds 1-10:
// keep_point_fej mean 3.2 mm, at most 5.75 mm, reuse 3.9 mm, at most 6.7 mm
// (docs/recorded_flights.md, "The mono configurations switched"). This
// seed: 0.018 deg, 4.9 mm, ATE 0.031 m, no reset (reuse: 0.020 deg, 4.0 mm).
// Earlier, 12 s with reuse: with the calibration prior (0.02 rad, 1 cm)
// 0.019 deg, 7.8 mm; before the prior 0.023 deg, 5.5 mm (1, 2 deg: 0.023,
// 0.029 deg, 5.6, 7.5 mm), and 3 deg once reset for too few landmarks at
// the end of the still start; a reset keeps the extrinsic estimate, so at
// most one is allowed.
TEST(EstimatorCalibration, ExtrinsicConvergesFromAPerturbedStart) {
  const Simulation sim = Simulate(AggressiveSimulation(20.0, false, 0.0));
  const std::vector<EstimatorCamera> truth = testing::Prepare(sim).cameras;
  std::vector<EstimatorCamera> perturbed = truth;
  const Eigen::Vector3d axis = Eigen::Vector3d(1.0, -2.0, 1.5).normalized();
  perturbed[0].T_b_c.linear() =
      truth[0].T_b_c.linear() * Exp(axis * (4.0 * M_PI / 180.0));
  perturbed[0].T_b_c.translation() += Eigen::Vector3d(0.03, -0.02, 0.015);
  EstimatorOptions options = testing::OptionsFor(sim.options);
  options.estimate_extrinsics = true;
  const SimReplay r = testing::ReplayWithCameras(sim, options, perturbed);
  const Eigen::Isometry3d error = truth[0].T_b_c.inverse() * r.T_b_c0;
  const Eigen::Isometry3d start = truth[0].T_b_c.inverse() * perturbed[0].T_b_c;
  std::printf(
      "T_b_c error: start %.2f deg %.4f m, end %.3f deg %.4f m; ATE %.4f m, "
      "resets %lld\n",
      RotationDeg(start.linear()), start.translation().norm(),
      RotationDeg(error.linear()), error.translation().norm(), r.ate_rmse_m,
      static_cast<long long>(r.summary.resets));
  for (const ResetEvent& e : r.summary.reset_log) {
    std::printf("reset at %.2f s: %d\n",
                1e-9 * static_cast<double>(e.t_ns - sim.options.start_time_ns),
                static_cast<int>(e.reason));
  }
  EXPECT_LE(r.summary.resets, 1);
  EXPECT_EQ(r.summary.frames_processed + r.summary.frames_before_init,
            r.summary.frames);
  EXPECT_LT(RotationDeg(error.linear()), 0.1);
  EXPECT_LT(error.translation().norm(), 0.01);
}

// T_b_c started at the truth and estimated must neither wander nor cost much
// accuracy. Without a prior on the calibration it had no information until
// the first marginalisation: during the still start and the first turns its
// translation is unobservable: it wandered up to 11.6 m (24 cm still at frame
// 40) and the marginalisation prior froze the drift in (ATE 0.087 m against
// 0.015 m with T_b_c fixed). With the calibration prior (1 cm, 0.02 rad):
// wander at most 1.9 cm (3.0 deg at one step), ATE 0.0275 m.
TEST(EstimatorCalibration,
     ExtrinsicStartedAtTheTruthNeitherWandersNorCostsMuchAccuracy) {
  const Simulation sim = Simulate(AggressiveSimulation(12.0, false, 0.0));
  const testing::PreparedSimulation prepared = testing::Prepare(sim);
  const Eigen::Isometry3d truth = prepared.cameras[0].T_b_c;
  EstimatorOptions options = testing::OptionsFor(sim.options);
  options.estimate_extrinsics = true;
  Estimator estimator(options, VisualFactorOptions(), sim.options.imu.noise,
                      PreintegrationOptions(), prepared.cameras);
  double max_wander_m = 0.0;
  double max_wander_deg = 0.0;
  RunSequence(
      &estimator, sim.imu, prepared.frames,
      [&](size_t, const EstimatorOutput&) {
        const Eigen::Isometry3d e = truth.inverse() * estimator.T_b_c(0);
        max_wander_m = std::max(max_wander_m, e.translation().norm());
        max_wander_deg = std::max(max_wander_deg, RotationDeg(e.linear()));
      });
  const SimReplay freed =
      testing::ReplayWithCameras(sim, options, prepared.cameras);
  const SimReplay fixed =
      testing::ReplaySimulation(sim, testing::OptionsFor(sim.options));
  std::printf(
      "T_b_c from the truth: wander up to %.4f m, %.3f deg; ATE %.4f m "
      "(fixed: %.4f m)\n",
      max_wander_m, max_wander_deg, freed.ate_rmse_m, fixed.ate_rmse_m);
  EXPECT_LT(max_wander_m, 0.03);
  EXPECT_LT(freed.ate_rmse_m, 2.5 * fixed.ate_rmse_m);
}

}  // namespace
}  // namespace vio
