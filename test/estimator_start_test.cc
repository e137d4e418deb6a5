// The estimator's starts end to end on simulations (issue 10): in motion
// (mono and stereo) against the simulator's truth, the refusal of degenerate
// motion with its reason, and the zero-velocity detector: holding a still
// start, never firing in slow motion.

#include <gtest/gtest.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>

#include "config/simulator_config.h"
#include "dataset/simulator.h"
#include "estimator/estimator.h"
#include "test/testing/sim_replay.h"

namespace vio {
namespace {

SimulatorOptions Preset(const std::string& name, double seconds) {
  SimulatorOptions o = LoadSimulatorOptions(std::string(VIO_SOURCE_DIR) +
                                            "/config/sim_" + name + ".yaml");
  o.duration_s = seconds;
  return o;
}

// One trial of a preset with 5 % outlier sightings (the init_benchmark's
// *_out5 copies): its seed and start phase.
Simulation SimulateWithOutliers(const std::string& preset, double seconds,
                                uint32_t seed, double phase_s) {
  SimulatorOptions o = Preset(preset, seconds);
  o.camera.outlier_fraction = 0.05;
  o.seed = seed;
  o.motion.start_phase_s = phase_s;
  return Simulate(o);
}

const StampedState& TruthAt(const Simulation& sim, int64_t t_ns) {
  const auto it = std::lower_bound(
      sim.ground_truth.begin(), sim.ground_truth.end(), t_ns,
      [](const StampedState& s, int64_t t) { return s.t_ns < t; });
  return it == sim.ground_truth.end() ? sim.ground_truth.back() : *it;
}

// RMS distance of the window's positions from their centroid.
template <typename Position>
double Spread(const std::vector<InitialFrame>& window, Position position) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const InitialFrame& f : window) c += position(f);
  c /= static_cast<double>(window.size());
  double s = 0.0;
  for (const InitialFrame& f : window) s += (position(f) - c).squaredNorm();
  return std::sqrt(s / static_cast<double>(window.size()));
}

// The first start against the truth.
struct StartCheck {
  InitMethod method = InitMethod::kAuto;
  double time_s = 0.0;       // from the first frame [s]
  double scale_error = 0.0;  // window spread against the truth's, - 1 [-]
  double gravity_deg = 0.0;  // world z seen from the newest frame [deg]
  double gyro_bias = 0.0;    // |b_g - truth| at the newest frame [rad/s]
};

StartCheck CheckFirstStart(const Simulation& sim,
                           const testing::SimReplay& run) {
  const StartRecord& start = run.summary.starts.front();
  StartCheck c;
  c.method = start.method;
  c.time_s = 1e-9 * static_cast<double>(start.t_ns - run.outputs.front().t_ns);
  const double est =
      Spread(start.window, [](const InitialFrame& f) { return f.p_w_b; });
  const double truth = Spread(start.window, [&](const InitialFrame& f) {
    return TruthAt(sim, f.t_imu_ns).p_w_b;
  });
  c.scale_error = est / truth - 1.0;
  const InitialFrame& newest = start.window.back();
  const StampedState& gt = TruthAt(sim, newest.t_imu_ns);
  const Eigen::Vector3d z_est =
      newest.q_w_b.conjugate() * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d z_true =
      gt.q_w_b.conjugate() * Eigen::Vector3d::UnitZ();
  c.gravity_deg =
      std::atan2(z_est.cross(z_true).norm(), z_est.dot(z_true)) * 180.0 / M_PI;
  c.gyro_bias = (newest.b_g - gt.b_g).norm();
  return c;
}

TEST(EstimatorStart, MonoStartsInMotionWithTheTrueScaleAndGravity) {
  const Simulation sim = Simulate(Preset("motion_mono", 4.0));
  const testing::SimReplay run =
      testing::ReplaySimulation(sim, testing::OptionsFor(sim.options));
  ASSERT_FALSE(run.summary.starts.empty()) << DescribeNoStart(run.summary);
  const StartCheck c = CheckFirstStart(sim, run);
  EXPECT_EQ(c.method, InitMethod::kMono);
  EXPECT_LE(c.time_s, 2.0);
  // The target is 3 %; this seed's start is 6.2 % off (the
  // distribution over 20 seeds: docs/initialisation.md).
  EXPECT_LT(std::abs(c.scale_error), 0.08);
  EXPECT_LT(c.gravity_deg, 1.0);
  // The truth's bias is 0.08 rad/s: fitted, not left at zero.
  EXPECT_LT(c.gyro_bias, 0.01);
  EXPECT_EQ(run.summary.resets, 0);
  EXPECT_LT(run.ate_rmse_m, 0.08);
}

// The hand-held preset (a small ellipse, fast-turning camera): its tracks
// leave the view within a second, so the reference pair is at most ~0.6 s
// old and its rotation-compensated parallax ~10-18 px. With the former
// 20 px threshold this seed never started within 6 s (`too little
// parallax` at every frame, docs/initialisation.md); the scale checks still
// guard the start. The structure-from-motion start alone: the
// gyroscope-aided fallback (on by default) starts this seed first, below.
TEST(EstimatorStart, HandHeldMonoStartsWithinTwoSeconds) {
  SimulatorOptions o = Preset("handheld", 3.0);
  o.seed = 1000;  // init_benchmark's first hand-held trial
  const Simulation sim = Simulate(o);
  EstimatorOptions options = testing::OptionsFor(sim.options);
  options.init.mono.gyro_aided = false;
  const testing::SimReplay run = testing::ReplaySimulation(sim, options);
  ASSERT_FALSE(run.summary.starts.empty()) << DescribeNoStart(run.summary);
  const StartCheck c = CheckFirstStart(sim, run);
  EXPECT_EQ(c.method, InitMethod::kMono);
  EXPECT_LE(c.time_s, 2.0);
  // Measured: 1.70 s, scale -9.7 %, gravity 0.91 deg.
  EXPECT_LT(std::abs(c.scale_error), 0.15);
  EXPECT_LT(c.gravity_deg, 1.5);
  EXPECT_LT(c.gyro_bias, 0.01);
}

// With the default options the gyroscope-aided fallback starts the same
// seed sooner, where the structure-from-motion start is refused (init_
// benchmark's trial 1000: 1.50 s, scale -17.0 %, gravity 0.72 deg; its
// scale error is within the 37.8 % the rule for turning it on compared
// against, docs/initialisation.md).
TEST(EstimatorStart, HandHeldDefaultStartsByTheGyroAidedFallback) {
  SimulatorOptions o = Preset("handheld", 3.0);
  o.seed = 1000;
  const Simulation sim = Simulate(o);
  const testing::SimReplay run =
      testing::ReplaySimulation(sim, testing::OptionsFor(sim.options));
  ASSERT_FALSE(run.summary.starts.empty()) << DescribeNoStart(run.summary);
  const StartCheck c = CheckFirstStart(sim, run);
  EXPECT_EQ(c.method, InitMethod::kGyroAided);
  EXPECT_LE(c.time_s, 1.55);
  EXPECT_LT(std::abs(c.scale_error), 0.25);
  EXPECT_LT(c.gravity_deg, 1.5);
  EXPECT_LT(c.gyro_bias, 0.01);
}

TEST(EstimatorStart, StereoStartsInMotionWithinHalfASecond) {
  const Simulation sim = Simulate(Preset("motion_stereo", 3.0));
  const testing::SimReplay run =
      testing::ReplaySimulation(sim, testing::OptionsFor(sim.options));
  ASSERT_FALSE(run.summary.starts.empty()) << DescribeNoStart(run.summary);
  const StartCheck c = CheckFirstStart(sim, run);
  EXPECT_EQ(c.method, InitMethod::kStereo);
  EXPECT_LE(c.time_s, 0.5);
  EXPECT_LT(std::abs(c.scale_error), 0.03);
  EXPECT_LT(c.gravity_deg, 1.0);
  EXPECT_LT(c.gyro_bias, 0.01);
  EXPECT_LT(run.ate_rmse_m, 0.05);
}

// testing::AteFrom (init_benchmark --against-default): from before the first
// output it is the replay's own ATE; from a stamp on, only those frames are
// aligned and counted; past the last frame there is nothing to evaluate.
TEST(EstimatorStart, AteFromCountsTheFramesFromAStampOn) {
  const Simulation sim = Simulate(Preset("motion_stereo", 3.0));
  const testing::SimReplay run =
      testing::ReplaySimulation(sim, testing::OptionsFor(sim.options));
  double all = -1.0;
  ASSERT_TRUE(testing::AteFrom(sim, run.outputs, INT64_MIN, &all));
  EXPECT_DOUBLE_EQ(all, run.ate_rmse_m);
  const int64_t last = run.outputs.back().t_ns;
  double none = -1.0;
  EXPECT_FALSE(testing::AteFrom(sim, run.outputs, last + 1, &none));
  double tail = -1.0;
  ASSERT_TRUE(testing::AteFrom(sim, run.outputs, last - 1'000'000'000, &tail));
  EXPECT_GT(tail, 0.0);
  EXPECT_NE(tail, all);
}

// Degenerate motion: no start is accepted, and the log says why.
testing::SimReplay ExpectRefused(const std::string& preset, InitFailure reason,
                                 bool gyro_aided = false,
                                 double seconds = 5.0) {
  const Simulation sim = Simulate(Preset(preset, seconds));
  EstimatorOptions options = testing::OptionsFor(sim.options);
  options.init.mono.gyro_aided = gyro_aided;
  const testing::SimReplay run = testing::ReplaySimulation(sim, options);
  EXPECT_TRUE(run.summary.starts.empty()) << preset;
  EXPECT_EQ(run.summary.frames_before_init, run.summary.frames);
  EXPECT_FALSE(run.summary.init_attempts.empty());
  // The static start is tried too (and refused: the features move); of the
  // in-motion attempts, most fail for `reason`.
  int in_motion = 0, with_reason = 0;
  for (const InitAttempt& a : run.summary.init_attempts) {
    if (a.method == InitMethod::kStatic) continue;
    ++in_motion;
    with_reason += a.reason == reason ? 1 : 0;
  }
  EXPECT_GT(in_motion, 0);
  // The reason is the main one, and the summary names it.
  EXPECT_GT(2 * with_reason, in_motion)
      << preset << ": " << DescribeNoStart(run.summary);
  EXPECT_NE(DescribeNoStart(run.summary).find(InitFailureName(reason)),
            std::string::npos);
  return run;
}

TEST(EstimatorStart, ConstantVelocityIsRefusedForLackOfExcitation) {
  ExpectRefused("line", InitFailure::kLowImuExcitation);
}

TEST(EstimatorStart, PureRotationIsRefusedForLackOfParallax) {
  ExpectRefused("rotation", InitFailure::kLowParallax);
}

TEST(EstimatorStart, PlanarCircleIsRefusedForLackOfExcitation) {
  // Constant speed and turn rate, no roll or pitch: a constant specific
  // force in the body frame, which the accelerometer bias could absorb.
  ExpectRefused("circle", InitFailure::kLowImuExcitation);
}

// With the gyroscope-aided fallback on, the degenerate presets are refused
// too. The pure rotation over its 15 s: with gyro_min_parallax_px at 4 px the
// fallback started sim_rotation's 15 s at 9.4 s (its parallax there, the
// camera's lever arm and noise, is 3.6-4.6 px); and after a window showed no
// translation the fallback waits kGyroAidedRetryAfterNoParallaxS before it
// tries again, doubled at each such refusal up to the window's 2 s (it paid
// ~0.1 s at every frame).
TEST(EstimatorStart, DegenerateMotionIsRefusedWithTheGyroAidedFallbackToo) {
  ExpectRefused("line", InitFailure::kLowImuExcitation, true);
  ExpectRefused("circle", InitFailure::kLowImuExcitation, true);
  const testing::SimReplay run =
      ExpectRefused("rotation", InitFailure::kLowParallax, true, 15.0);
  int gyro = 0;
  int64_t last = INT64_MIN, closest = INT64_MAX, widest = 0;
  for (const InitAttempt& a : run.summary.init_attempts) {
    if (a.method != InitMethod::kGyroAided ||
        a.reason == InitFailure::kTooFewFrames) {
      continue;
    }
    ++gyro;
    if (last != INT64_MIN) {
      closest = std::min(closest, a.t_ns - last);
      widest = std::max(widest, a.t_ns - last);
    }
    last = a.t_ns;
  }
  // 13.5 s after the span fills (270 frames): waits of 0.25, 0.5, 1, 2, 2,
  // ... s, never longer than the window (a start is delayed by at most it).
  EXPECT_GE(gyro, 5);
  EXPECT_LE(gyro, 14);
  EXPECT_GE(closest, std::llround(kGyroAidedRetryAfterNoParallaxS * 1e9));
  EXPECT_LE(widest, std::llround(2.05e9));
}

TEST(EstimatorStart, StillStartIsHeldStillByTheZeroMotionFactor) {
  // The default preset: 2 s still, then the ellipse.
  SimulatorOptions o = Preset("default", 3.0);
  const Simulation sim = Simulate(o);
  EstimatorOptions options = testing::OptionsFor(o);
  const testing::SimReplay held = testing::ReplaySimulation(sim, options);
  options.zero_velocity.enabled = false;
  const testing::SimReplay free = testing::ReplaySimulation(sim, options);
  ASSERT_FALSE(held.summary.starts.empty());
  EXPECT_EQ(held.summary.starts.front().method, InitMethod::kStatic);
  EXPECT_GT(held.summary.zero_velocity_frames, 0);
  EXPECT_EQ(free.summary.zero_velocity_frames, 0);
  // How far each moves from its first estimate while still (truth: 0).
  auto moved = [&](const testing::SimReplay& run) {
    double worst = 0.0;
    const EstimatorOutput* first = nullptr;
    for (const EstimatorOutput& out : run.outputs) {
      if (out.t_ns - sim.ground_truth.front().t_ns > 1'900'000'000) break;
      if (!out.initialized) continue;
      if (first == nullptr) first = &out;
      worst = std::max(worst, (out.p_w_b - first->p_w_b).norm());
    }
    return worst;
  };
  EXPECT_LT(moved(held), 0.01);
  EXPECT_LT(moved(held), moved(free));
}

TEST(EstimatorStart, StereoStartAtRestIsHeldStillToo) {
  // In stereo, auto starts in motion after 0.45 s (before the static start's
  // 1 s): the zero-velocity detector must hold the rest of the still start.
  SimulatorOptions o = Preset("stereo", 3.0);
  const Simulation sim = Simulate(o);
  const testing::SimReplay run =
      testing::ReplaySimulation(sim, testing::OptionsFor(o));
  ASSERT_FALSE(run.summary.starts.empty());
  EXPECT_EQ(run.summary.starts.front().method, InitMethod::kStereo);
  EXPECT_GT(run.summary.zero_velocity_frames, 10);
}

// The joint adjustment's change of the window's path length is reported as a
// scale change only where the window's path defines a scale: at rest the
// path is position noise (the still stereo start printed "moved the scale
// -91.6 %"), in motion it is the scale (estimator/initial_window.h).
TEST(EstimatorStart, ScaleChangeIsNotMeaningfulAtRestButIsInMotion) {
  const Simulation still = Simulate(Preset("stereo", 1.0));
  const testing::SimReplay rest =
      testing::ReplaySimulation(still, testing::OptionsFor(still.options));
  ASSERT_FALSE(rest.summary.starts.empty());
  const InitDiagnostics& at_rest = rest.summary.starts.front().diagnostics;
  EXPECT_EQ(rest.summary.starts.front().method, InitMethod::kStereo);
  EXPECT_FALSE(ScaleChangeDefined(at_rest))
      << "path " << at_rest.refined_path_m << " m, change "
      << at_rest.refine_scale_change << ", spread sigma "
      << at_rest.refined_scale_sigma;
  const Simulation moving = Simulate(Preset("motion_stereo", 1.0));
  const testing::SimReplay run =
      testing::ReplaySimulation(moving, testing::OptionsFor(moving.options));
  ASSERT_FALSE(run.summary.starts.empty());
  const InitDiagnostics& in_motion = run.summary.starts.front().diagnostics;
  EXPECT_TRUE(ScaleChangeDefined(in_motion))
      << "spread sigma " << in_motion.refined_scale_sigma;
  EXPECT_LT(in_motion.refined_scale_sigma, 0.05);
}

// Four of init_benchmark's motion_stereo trials (seed, start phase) whose
// stereo start was refused past 0.5 s: 1001, 1003 and 1012 at the 0.4 s span
// on the PnP trajectory's |g| or rotations before the later frames were
// placed on chained stereo points and |g| was judged in its own sigmas;
// 1007 and 1012 at the 0.45 s span on a rotation misfit of 0.53 deg (limit
// 0.5) and a |g| 3.5 of its own sigmas off (limit 3) before those checks were
// set for a failed PnP (estimator/in_motion_start.cc; docs/initialisation.md,
// "The 0.45 s stereo span"): now each starts by 0.5 s, its tilt within
// 1.5 deg.
TEST(EstimatorStart, StereoStartInMotionWithinHalfASecond) {
  const struct {
    uint32_t seed;
    double phase_s;
  } trials[] = {{1001, 3.75}, {1003, 5.25}, {1007, 8.25}, {1012, 12.0}};
  for (const auto& trial : trials) {
    SimulatorOptions o = Preset("motion_stereo", 0.7);
    o.seed = trial.seed;
    o.motion.start_phase_s = trial.phase_s;
    const Simulation sim = Simulate(o);
    const testing::SimReplay run =
        testing::ReplaySimulation(sim, testing::OptionsFor(o));
    ASSERT_FALSE(run.summary.starts.empty()) << DescribeNoStart(run.summary);
    const StartCheck c = CheckFirstStart(sim, run);
    EXPECT_EQ(c.method, InitMethod::kStereo);
    EXPECT_LE(c.time_s, 0.5) << "seed " << trial.seed;
    EXPECT_LT(c.gravity_deg, 1.5) << "seed " << trial.seed;
    std::printf("seed %u: stereo start after %.2f s, gravity %.2f deg\n",
                trial.seed, c.time_s, c.gravity_deg);
  }
}

// The stereo start with 5 % outlier sightings (camera.outlier_fraction):
// these trials started tens of percent off in scale on init_benchmark before
// the outlier rounds of the start's joint adjustment
// (init.stereo.refine_outlier_rounds; docs/initialisation.md, "The stereo
// start with outliers"); with the rounds set to 0, seed 1008 started +29.4 %
// off and seed 1010 not within the 1 s. Seeds 1007 and 1010 then started
// only after 0.65 and 0.75 s: their first attempts were refused with
// rotation misfits of 1.5-96 deg, the chained PnP placing frames tens of
// degrees off (OpenCV's RANSAC refining from its last sample; estimator/
// structure_from_motion_pnp.cc, PlaceCameraByPnp). Each now starts by 0.5 s and
// within 5 % of the true scale.
TEST(EstimatorStart, StereoStartWithOutliersKeepsItsScale) {
  const struct {
    uint32_t seed;
    double phase_s;
  } trials[] = {{1007, 8.25}, {1008, 9.0}, {1010, 10.5}, {1015, 14.25}};
  for (const auto& trial : trials) {
    const Simulation sim =
        SimulateWithOutliers("motion_stereo", 1.0, trial.seed, trial.phase_s);
    const testing::SimReplay run =
        testing::ReplaySimulation(sim, testing::OptionsFor(sim.options));
    ASSERT_FALSE(run.summary.starts.empty()) << DescribeNoStart(run.summary);
    const StartCheck c = CheckFirstStart(sim, run);
    EXPECT_LE(c.time_s, 0.5) << "seed " << trial.seed;
    EXPECT_LT(std::abs(c.scale_error), 0.05) << "seed " << trial.seed;
    std::printf("seed %u: start after %.2f s, scale %+.1f %%\n", trial.seed,
                c.time_s, 100.0 * c.scale_error);
  }
}

// The same preset where the start's first solve ran away: with every outlier
// sighting in, the joint adjustment's first solve ended at several times the
// true scale, the outlier rounds then removed good sightings against that
// state, and main's start ended 6.0 % (seed 1008), 3.8 % (seed 1029) and
// 21 % (seed 1048) off in scale, accepted (init_benchmark
// --preset motion_stereo_out5, --seeds 40 and --first-seed 1020 --seeds 40).
// The sightings off by more than init.stereo.refine_prescreen_threshold_px
// at the alignment's state are now removed before that solve
// (docs/initialisation.md, "The first solve with outliers: gross outliers
// out before it"); with that removal skipped, these trials end +6.03,
// +3.78 and -20.97 % off again.
TEST(EstimatorStart, StereoStartRemovesGrossOutliersBeforeItsFirstSolve) {
  const struct {
    uint32_t seed;
    double phase_s;
  } trials[] = {{1008, 6.0}, {1029, 13.875}, {1048, 13.5}};
  for (const auto& trial : trials) {
    const Simulation sim =
        SimulateWithOutliers("motion_stereo", 1.0, trial.seed, trial.phase_s);
    EstimatorOptions options = testing::OptionsFor(sim.options);
    ASSERT_GT(options.init.stereo.refine_prescreen_threshold_px, 0.0);
    const testing::SimReplay run = testing::ReplaySimulation(sim, options);
    ASSERT_FALSE(run.summary.starts.empty()) << DescribeNoStart(run.summary);
    const StartCheck c = CheckFirstStart(sim, run);
    EXPECT_EQ(c.method, InitMethod::kStereo) << "seed " << trial.seed;
    EXPECT_LE(c.time_s, 0.5) << "seed " << trial.seed;
    EXPECT_LT(std::abs(c.scale_error), 0.03) << "seed " << trial.seed;
    EXPECT_GT(run.summary.starts.front().diagnostics.refine_prescreen_removed,
              0)
        << "seed " << trial.seed;
    std::printf("seed %u: start after %.2f s, scale %+.2f %%\n", trial.seed,
                c.time_s, 100.0 * c.scale_error);
  }
}

// The mono start in motion with 5 % outlier sightings (init_benchmark's
// motion_mono_out5 and handheld_out5, docs/initialisation.md, "The mono
// start in motion with outliers"): the structure from motion removes them
// (init.mono.outlier_rounds) and starts within 2 s. Before, its RMS over
// every sighting (28-41 px at the least) refused every mono attempt and
// these trials started by the gyroscope-aided fallback or not at all within
// 6 s. Measured: 1.90 s -15.7 %, 1.85 s +10.1 %, 1.50 s -5.4 %.
TEST(EstimatorStart, MonoStartWithOutliersStartsWithinTwoSeconds) {
  const struct {
    const char* preset;
    uint32_t seed;
    double phase_s;
  } trials[] = {{"motion_mono", 1000, 3.0},
                {"motion_mono", 1001, 6.75},
                {"handheld", 1001, 3.5}};
  for (const auto& trial : trials) {
    const Simulation sim =
        SimulateWithOutliers(trial.preset, 2.5, trial.seed, trial.phase_s);
    const testing::SimReplay run =
        testing::ReplaySimulation(sim, testing::OptionsFor(sim.options));
    ASSERT_FALSE(run.summary.starts.empty()) << DescribeNoStart(run.summary);
    const StartCheck c = CheckFirstStart(sim, run);
    EXPECT_EQ(c.method, InitMethod::kMono) << trial.preset << " " << trial.seed;
    EXPECT_LE(c.time_s, 2.0) << trial.preset << " " << trial.seed;
    EXPECT_LT(std::abs(c.scale_error), 0.2)
        << trial.preset << " " << trial.seed;
    EXPECT_LT(c.gravity_deg, 2.0) << trial.preset << " " << trial.seed;
    std::printf(
        "%s seed %u: start after %.2f s, scale %+.1f %%, gravity %.2f deg\n",
        trial.preset, trial.seed, c.time_s, 100.0 * c.scale_error,
        c.gravity_deg);
  }
}

// The hand-held copy with 5 % outlier sightings (init_benchmark --preset
// handheld_out5 --seeds 20): the joint adjustment that completes a mono
// start removed no outliers (the stereo start's rounds only) and main
// accepted trial 1016 at +87.5 % and 1008 at -50.6 %. The joint
// adjustment's outlier rounds now apply to mono starts too
// (init.mono.refine_outlier_rounds): 1008 starts at -41.9 % (2 landmarks
// behind their anchor removed; the rest of its error is the adjustment's
// trade of b_a against scale, docs/initialisation.md), 1016 by the
// gyroscope-aided fallback at +17.2 % (2 gross outliers removed before its
// first solve). With the rounds skipped for mono starts these trials end at
// -50.6 and +87.5 % again.
TEST(EstimatorStart, MonoStartWithOutliersRemovesThemInItsJointAdjustment) {
  const struct {
    uint32_t seed;
    double phase_s;
  } trials[] = {{1008, 5.0}, {1016, 9.0}};
  for (const auto& trial : trials) {
    const Simulation sim =
        SimulateWithOutliers("handheld", 6.0, trial.seed, trial.phase_s);
    EstimatorOptions options = testing::OptionsFor(sim.options);
    ASSERT_GT(options.init.mono.refine_outlier_rounds, 0);
    const testing::SimReplay run = testing::ReplaySimulation(sim, options);
    ASSERT_FALSE(run.summary.starts.empty()) << DescribeNoStart(run.summary);
    const StartCheck c = CheckFirstStart(sim, run);
    EXPECT_LT(std::abs(c.scale_error), 0.45) << "seed " << trial.seed;
    std::printf("seed %u: %s start after %.2f s, scale %+.1f %%\n", trial.seed,
                InitMethodName(c.method), c.time_s, 100.0 * c.scale_error);
  }
}

TEST(EstimatorStart, ZeroVelocityNeverFiresInSlowMotion) {
  // 2 s still, a 2 s blend, then ~0.1 m/s with accelerations the IMU test
  // cannot tell from rest: the image test must keep the detector quiet
  // once the camera moves (zero_velocity.h: faster than ~3 cm/s).
  const Simulation sim = Simulate(Preset("slow", 8.0));
  const testing::SimReplay run =
      testing::ReplaySimulation(sim, testing::OptionsFor(sim.options));
  ASSERT_FALSE(run.summary.starts.empty());
  int64_t held = 0, moving = 0;
  double fastest_held = 0.0;
  for (const EstimatorOutput& out : run.outputs) {
    if (!out.initialized) continue;
    const double speed = TruthAt(sim, out.t_ns).v_w.norm();
    moving += speed > 0.03 ? 1 : 0;
    if (!out.zero_velocity) continue;
    ++held;
    fastest_held = std::max(fastest_held, speed);
  }
  EXPECT_GT(held, 10);    // the still start is held
  EXPECT_GT(moving, 50);  // and most of the run moves
  EXPECT_LT(fastest_held, 0.03);
}

}  // namespace
}  // namespace vio
