// Re-initialisation after a failure reset (init.reinitialize_after_reset,
// docs/initialisation.md): one provoked reset in the middle of a mono run in
// motion, replayed with the option off (the default: the window restarts
// from the IMU prediction and keeps its landmarks) and on (the in-motion
// initialiser runs again from the reset on and its window replaces the
// restarted one, the running position and yaw kept). Each path must do what
// it says. Which one is the default is decided over 35 resets per
// configuration (scripts/reinit_table.sh, docs/initialisation.md), not on
// this one: with the built-in defaults since the mono switch (landmarks kept
// as world points) the re-initialisation is the better here (ATE 0.0401 m
// against 0.0765 m) while over the 35 mono resets it is worse at the median
// (docs/initialisation.md, "On mono with the landmarks kept as world
// points"), so the default stays off and this reset no longer holds it.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "config/estimator_config.h"
#include "config/imu_config.h"
#include "config/simulator_config.h"
#include "config/yaml_reader.h"
#include "dataset/fault_injection.h"
#include "dataset/simulator.h"
#include "estimator/estimator.h"
#include "test/testing/sim_replay.h"

namespace vio {
namespace {

using testing::SimReplay;

// The preset config/sim_<preset>.yaml, its first `seconds`.
Simulation SimulatePreset(const std::string& preset, double seconds) {
  SimulatorOptions o = LoadSimulatorOptions(std::string(VIO_SOURCE_DIR) +
                                            "/config/sim_" + preset + ".yaml");
  o.duration_s = seconds;
  return Simulate(o);
}

// The default preset (2 s still, then the ellipse), mono, 10 s.
const Simulation& Sequence() {
  static const Simulation* simulation =
      new Simulation(SimulatePreset("default", 10.0));
  return *simulation;
}

// One accelerometer value of 1e6 m/s^2 at 4.93 s with the range check off:
// the state explodes and the pre-solve check resets the window while moving
// (~1.5 m/s).
SimReplay RunWithReset(bool reinitialize) {
  EstimatorOptions options = testing::OptionsFor(Sequence().options);
  options.imu_stream.range.accelerometer_range =
      std::numeric_limits<double>::max();
  options.init.reinitialize_after_reset = reinitialize;
  ImuFault fault;
  fault.kind = ImuFaultKind::kAccelValue;
  fault.t_s = 4.93;
  fault.count = 1;
  fault.value = 1e6;
  return testing::Replay(Sequence(), options,
                         WithImuFault(Sequence().imu, fault),
                         testing::Prepare(Sequence()).frames);
}

const SimReplay& Off() {
  static const SimReplay* run = new SimReplay(RunWithReset(false));
  return *run;
}

const SimReplay& On() {
  static const SimReplay* run = new SimReplay(RunWithReset(true));
  return *run;
}

const StampedState& TruthAt(const Simulation& sim, int64_t t_ns) {
  const auto& gt = sim.ground_truth;
  const auto it = std::lower_bound(
      gt.begin(), gt.end(), t_ns,
      [](const StampedState& s, int64_t t) { return s.t_ns < t; });
  return it == gt.end() ? gt.back() : *it;
}

// RMS spread of the window's positions about their centroid, estimated
// against the truth's, minus 1.
double ScaleError(const StartRecord& start) {
  auto spread = [&](bool truth) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (const InitialFrame& f : start.window) {
      c += truth ? TruthAt(Sequence(), f.t_imu_ns).p_w_b : f.p_w_b;
    }
    c /= static_cast<double>(start.window.size());
    double s = 0.0;
    for (const InitialFrame& f : start.window) {
      s += ((truth ? TruthAt(Sequence(), f.t_imu_ns).p_w_b : f.p_w_b) - c)
               .squaredNorm();
    }
    return std::sqrt(s / static_cast<double>(start.window.size()));
  };
  return spread(false) / spread(true) - 1.0;
}

// The step into the frame at t_ns from the one before it, estimated against
// true, in the earlier frame's body axes (so free of the gauge): how far the
// output jumps there [m] and how much it turns beyond the true turn [rad].
// (The simulation has no camera time offset: frame stamps are truth stamps.)
struct Jump {
  double position_m = 0.0;
  double rotation_rad = 0.0;
};
Jump JumpAt(const Simulation& sim, const SimReplay& r, int64_t t_ns) {
  Jump jump;
  for (size_t k = 1; k < r.outputs.size(); ++k) {
    if (r.outputs[k].t_ns != t_ns) continue;
    const EstimatorOutput& a = r.outputs[k - 1];
    const EstimatorOutput& b = r.outputs[k];
    const StampedState& ta = TruthAt(sim, a.t_ns);
    const StampedState& tb = TruthAt(sim, b.t_ns);
    const Eigen::Vector3d step = a.q_w_b.conjugate() * (b.p_w_b - a.p_w_b);
    const Eigen::Vector3d true_step =
        ta.q_w_b.conjugate() * (tb.p_w_b - ta.p_w_b);
    jump.position_m = (step - true_step).norm();
    jump.rotation_rad = (a.q_w_b.conjugate() * b.q_w_b)
                            .angularDistance(ta.q_w_b.conjugate() * tb.q_w_b);
    return jump;
  }
  jump.position_m = jump.rotation_rad = std::numeric_limits<double>::infinity();
  return jump;
}

void ExpectResetWhileMoving(const Simulation& sim, const SimReplay& r,
                            InitMethod first_start = InitMethod::kStatic) {
  ASSERT_GE(r.summary.resets, 1);
  EXPECT_EQ(r.summary.reset_log[0].reason, Failure::kUnsafeState);
  ASSERT_FALSE(r.summary.starts.empty());
  EXPECT_EQ(r.summary.starts.front().method, first_start);
  EXPECT_FALSE(r.summary.starts.front().restart);
  // Moving at the reset: the case the option is for.
  EXPECT_GT(TruthAt(sim, r.summary.reset_log[0].t_ns).v_w.norm(), 0.5);
  // No frame after the first start loses its pose to the reset.
  EXPECT_EQ(r.summary.frames_processed + r.summary.frames_before_init,
            r.summary.frames);
  for (const EstimatorOutput& o : r.outputs) {
    ASSERT_TRUE(o.p_w_b.allFinite() && o.v_w.allFinite()) << o.t_ns;
  }
  // The restart frame moves on from the last output by the true step: its
  // position at the last velocity, its attitude by the gyroscope. Held at
  // the last output it lagged one frame step (0.054 m at ~1.1 m/s, and the
  // turn over the step), an offset the restarted window never removes.
  const Jump at_reset = JumpAt(sim, r, r.summary.reset_log[0].t_ns);
  std::printf("step into the reset frame against true: %.4f m, %.3f deg\n",
              at_reset.position_m, at_reset.rotation_rad * 180.0 / M_PI);
  EXPECT_LT(at_reset.position_m, 0.01);
  EXPECT_LT(at_reset.rotation_rad, 0.05 * M_PI / 180.0);
}

TEST(Reinitialization, OffTheResetOnlyRestartsFromThePrediction) {
  const SimReplay& r = Off();
  ExpectResetWhileMoving(Sequence(), r);
  EXPECT_EQ(r.summary.reinitializations, 0);
  EXPECT_EQ(r.summary.starts.size(), 1u);
  // The restart keeps the running state: the run stays near the truth
  // (measured 0.187 m with the reset, 0.241 m re-initialised).
  EXPECT_LT(r.ate_rmse_m, 0.3);
}

TEST(Reinitialization, OnTheInMotionStartReplacesTheRestartedWindow) {
  const SimReplay& r = On();
  ExpectResetWhileMoving(Sequence(), r);
  ASSERT_GE(r.summary.reinitializations, 1);
  // The second start is the re-initialisation: mono, in motion, after the
  // reset, once the frames since it span init.mono.min_span_s.
  ASSERT_GE(r.summary.starts.size(), 2u);
  const StartRecord& again = r.summary.starts[1];
  EXPECT_TRUE(again.restart);
  EXPECT_EQ(again.method, InitMethod::kMono);
  const double after_s =
      1e-9 * static_cast<double>(again.t_ns - r.summary.reset_log[0].t_ns);
  const EstimatorOptions defaults = testing::OptionsFor(Sequence().options);
  EXPECT_GE(after_s, defaults.init.mono.min_span_s - 0.05);
  EXPECT_LE(after_s, defaults.init.mono.long_window_s + 1.0);
  // A window of the in-motion start (not the one-frame restart): frames
  // spanning at least min_span_s, every one a keyframe of the new window.
  ASSERT_GE(again.window.size(), 3u);
  EXPECT_GE(1e-9 * static_cast<double>(again.window.back().t_ns -
                                       again.window.front().t_ns),
            defaults.init.mono.min_span_s - 0.05);
  EXPECT_GE(again.window.front().t_ns, r.summary.reset_log[0].t_ns);
  // The trajectory continues through the re-start: no jump beyond a
  // frame's error. Before the re-start held its gauge on the frame given the
  // running pose, a scale change in its adjustment moved that frame 0.86 m;
  // with the yaw taken from the heading of body x (nearly vertical on this
  // IMU) its attitude turned by tens of degrees in the stereo presets.
  const Jump jump = JumpAt(Sequence(), r, again.t_ns);
  EXPECT_LT(jump.position_m, 0.1);
  EXPECT_LT(jump.rotation_rad, 2.0 * M_PI / 180.0);
  // Its scale against the truth, for the docs (measured +55 %, where the
  // joint adjustment's own covariance claims 14 %: the accelerometer bias
  // and the scale trade off over these 2 s, docs/initialisation.md).
  std::printf(
      "re-start at %.2f s after the reset: scale error %+.1f %% "
      "(claimed sigma %.1f %%), jump %.3f m, %.2f deg\n",
      after_s, 100.0 * ScaleError(again),
      100.0 * again.diagnostics.refined_scale_sigma, jump.position_m,
      jump.rotation_rad * 180.0 / M_PI);
  EXPECT_GT(r.ate_rmse_m, 0.0);
}

// Stereo: the stereo preset (2 s still, then the ellipse), 8 s, replayed with
// the shipped config/stereo.yaml (its estimator: and imu: blocks) with the
// option on, the same fault at 6.03 s (~1.3 m/s). The stereo re-start is
// not the default (docs/initialisation.md: a tie at the median over 35
// resets); this holds that the path works when chosen: a stereo start soon
// after the reset, no jump, the run near the truth.
const Simulation& StereoSequence() {
  static const Simulation* simulation =
      new Simulation(SimulatePreset("stereo", 8.0));
  return *simulation;
}

TEST(Reinitialization, OnStereoTheReStartIsAStereoStartWithoutAJump) {
  const YamlNode root =
      YamlNode::LoadFile(std::string(VIO_SOURCE_DIR) + "/config/stereo.yaml");
  EstimatorOptions options = ReadEstimatorOptions(root);
  ApplyImuConfig(LoadImuConfig(root), &options);
  ASSERT_TRUE(options.use_stereo);
  options.imu_stream.range.accelerometer_range =
      std::numeric_limits<double>::max();
  options.init.reinitialize_after_reset = true;
  ImuFault fault;
  fault.kind = ImuFaultKind::kAccelValue;
  fault.t_s = 6.03;
  fault.count = 1;
  fault.value = 1e6;
  const Simulation& sim = StereoSequence();
  const SimReplay r =
      testing::Replay(sim, options, WithImuFault(sim.imu, fault),
                      testing::Prepare(sim).frames);
  // With the shipped stereo config the first start is a stereo one, in the
  // blend from rest to the ellipse.
  ExpectResetWhileMoving(sim, r, InitMethod::kStereo);
  ASSERT_GE(r.summary.reinitializations, 1);
  ASSERT_GE(r.summary.starts.size(), 2u);
  const StartRecord& again = r.summary.starts[1];
  EXPECT_TRUE(again.restart);
  EXPECT_EQ(again.method, InitMethod::kStereo);
  EXPECT_GE(again.window.front().t_ns, r.summary.reset_log[0].t_ns);
  // A stereo start needs init.stereo.min_span_s of frames (0.45 s; the
  // docs' table, at the former 0.4 s: 0.40-0.70 s after the reset on all
  // seven sequences).
  const double after_s =
      1e-9 * static_cast<double>(again.t_ns - r.summary.reset_log[0].t_ns);
  EXPECT_GE(after_s, options.init.stereo.min_span_s - 0.05);
  EXPECT_LE(after_s, 1.0);
  // The gauge kept: before YawBetween, the stereo re-start's attitude
  // jumped by 48.6 deg (docs/initialisation.md). Now 0.0075 m and 1.40 deg:
  // the gauge keeps the yaw, not the tilt, and a stereo start's gravity is
  // 0.66-0.81 deg off at the median over its 0.45 s span (same bound as
  // mono; measured here 1.40 deg, 1.51 with the former 0.4 s, 1.48 with
  // 0.35 s).
  const Jump jump = JumpAt(sim, r, again.t_ns);
  std::printf(
      "stereo re-start %.2f s after the reset: jump %.4f m, %.3f deg; "
      "ATE %.4f m\n",
      after_s, jump.position_m, jump.rotation_rad * 180.0 / M_PI,
      r.ate_rmse_m);
  EXPECT_LT(jump.position_m, 0.05);
  EXPECT_LT(jump.rotation_rad, 2.0 * M_PI / 180.0);
  EXPECT_GT(r.ate_rmse_m, 0.0);
  EXPECT_LT(r.ate_rmse_m, 0.05);
}

}  // namespace
}  // namespace vio
