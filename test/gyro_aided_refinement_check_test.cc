// The checks on the joint adjustment of a gyroscope-aided start
// (estimator/gyro_aided_refinement_check.h): the rule itself, and the two
// init_benchmark trials it was measured on (docs/initialisation.md), where
// without it a start 42.7 % (hand-held) and 48.4 % (motion_mono) off the
// true scale was accepted.

#include "estimator/gyro_aided_refinement_check.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "config/simulator_config.h"
#include "dataset/simulator.h"
#include "estimator/estimator.h"
#include "test/testing/sim_replay.h"
#include "test/testing/spread.h"

namespace vio {
namespace {

MonoInitOptions Limits() {
  MonoInitOptions m;
  m.max_scale_uncertainty = 0.25;
  m.gyro_max_refine_change_sigmas = 3.0;
  return m;
}

TEST(GyroAidedRefinementCheck, AcceptsAMoveWithinItsSigmas) {
  double value = 0.0, limit = 0.0;
  // log(1.5) = 0.405 = 2.7 sigmas of 15 %.
  EXPECT_EQ(CheckGyroAidedRefinement(0.5, 0.15, Limits(), &value, &limit),
            InitFailure::kNone);
  EXPECT_EQ(CheckGyroAidedRefinement(0.0, 0.0, Limits(), &value, &limit),
            InitFailure::kNone);
}

TEST(GyroAidedRefinementCheck, RefusesAMoveOfMoreSigmasEitherWay) {
  double value = 0.0, limit = 0.0;
  // Halving and doubling are the same move in log terms: 0.693 / 0.2 = 3.47.
  for (const double change : {-0.5, 1.0}) {
    EXPECT_EQ(CheckGyroAidedRefinement(change, 0.2, Limits(), &value, &limit),
              InitFailure::kRefinementScaleChange)
        << change;
    EXPECT_NEAR(value, std::log(2.0) / 0.2, 1e-9);
    EXPECT_EQ(limit, 3.0);
  }
  // A collapse to zero scale is refused, not a division by zero.
  EXPECT_EQ(CheckGyroAidedRefinement(-1.0, 0.2, Limits(), &value, &limit),
            InitFailure::kRefinementScaleChange);
}

TEST(GyroAidedRefinementCheck, RefusesAnUndeterminedOrUnknownScale) {
  double value = 0.0, limit = 0.0;
  EXPECT_EQ(CheckGyroAidedRefinement(0.0, 0.3, Limits(), &value, &limit),
            InitFailure::kScaleUncertain);
  EXPECT_EQ(value, 0.3);
  EXPECT_EQ(limit, 0.25);
  EXPECT_EQ(CheckGyroAidedRefinement(0.0, -1.0, Limits(), &value, &limit),
            InitFailure::kScaleUncertain);
}

// The first start of one init_benchmark trial (seed, start phase) with the
// gyroscope-aided fallback on, and the refusals logged before it.
struct Trial {
  bool started = false;
  InitMethod method = InitMethod::kAuto;
  double scale_error = 0.0;  // the window's spread against the truth's - 1
  int refusals = 0;          // gyro-aided attempts refused for `reason`
};

using vio::testing::Spread;

Trial RunTrial(const std::string& preset, uint32_t seed, double phase_s,
               InitFailure reason, double gyro_min_parallax_px = -1.0) {
  SimulatorOptions o = LoadSimulatorOptions(std::string(VIO_SOURCE_DIR) +
                                            "/config/sim_" + preset + ".yaml");
  o.seed = seed;
  o.motion.start_phase_s = phase_s;
  o.duration_s = 1.75;
  const Simulation sim = Simulate(o);
  EstimatorOptions options = testing::OptionsFor(sim.options);
  options.init.mono.gyro_aided = true;
  if (gyro_min_parallax_px > 0.0) {
    options.init.mono.gyro_min_parallax_px = gyro_min_parallax_px;
  }
  const testing::SimReplay run = testing::ReplaySimulation(sim, options);
  Trial t;
  for (const InitAttempt& a : run.summary.init_attempts) {
    if (a.method == InitMethod::kGyroAided && a.reason == reason) ++t.refusals;
  }
  if (run.summary.starts.empty()) return t;
  const StartRecord& start = run.summary.starts.front();
  t.started = true;
  t.method = start.method;
  std::vector<Eigen::Vector3d> est, truth;
  for (const InitialFrame& f : start.window) {
    est.push_back(f.p_w_b);
    const auto it = std::lower_bound(
        sim.ground_truth.begin(), sim.ground_truth.end(), f.t_imu_ns,
        [](const StampedState& s, int64_t t) { return s.t_ns < t; });
    truth.push_back(it->p_w_b);
  }
  t.scale_error = Spread(est) / Spread(truth) - 1.0;
  return t;
}

// Hand-held trial 1009: the gyroscope-aided solution at 1.55 s is +16.9 %
// off, the joint adjustment takes it to -42.7 % (3.5 of its claimed 20 %);
// refused, the SfM start follows at 1.60 s with -37 % (measured). Measured
// with gyro_min_parallax_px at 4 px, and held there: at 6 px (now) that
// attempt keeps fewer tracks and is refused before its adjustment (the SfM
// start follows all the same), so the check would not be exercised.
TEST(GyroAidedRefinementCheck, RefusesTheHandHeldStartTheAdjustmentMovesTooFar) {
  const Trial t = RunTrial("handheld", 1009, 5.5,
                           InitFailure::kRefinementScaleChange, 4.0);
  EXPECT_GE(t.refusals, 1);
  if (t.started) {
    EXPECT_LT(std::abs(t.scale_error), 0.4) << t.scale_error;
  }
}

// motion_mono trial 1012: the gyroscope-aided start at 1.55 s, whose
// adjusted window claims its scale to 32.7 % only, was +48.4 % off;
// refused, the gyroscope-aided start at 1.65 s is -2.9 % off (measured).
TEST(GyroAidedRefinementCheck, RefusesTheMotionMonoStartWithAnUndeterminedScale) {
  const Trial t =
      RunTrial("motion_mono", 1012, 12.0, InitFailure::kScaleUncertain);
  EXPECT_GE(t.refusals, 1);
  ASSERT_TRUE(t.started);
  EXPECT_LT(std::abs(t.scale_error), 0.3) << t.scale_error;
}

}  // namespace
}  // namespace vio
