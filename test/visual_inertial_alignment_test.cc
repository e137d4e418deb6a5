#include "estimator/visual_inertial_alignment.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "dataset/simulator.h"
#include "geometry/so3.h"

namespace vio {
namespace {

// The simulator's EuRoC camera-0 extrinsic.
Eigen::Isometry3d CameraExtrinsic() {
  const CameraCalibration c = EurocCam0Calibration();
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = c.q_b_c.toRotationMatrix();
  T.translation() = c.t_b_c;
  return T;
}

// A visual trajectory cut from a simulation in motion, expressed as an
// initialiser sees it: in the frame v of the first camera, divided by
// `scale`; plus the truth it must give back.
struct Scenario {
  std::vector<AlignmentFrame> frames;
  std::vector<ImuPreintegration> intervals;
  std::vector<Eigen::Vector3d> v_v;  // true velocities in v [m/s]
  Eigen::Vector3d g_v;               // true gravity in v [m/s^2]
  Eigen::Vector3d b_a, b_g;          // true biases at the start
  double scale = 1.0;                // metres per visual unit
};

struct Noise {
  double position_m = 0.0;    // added to each camera position [m]
  double rotation_rad = 0.0;  // per axis, on each attitude [rad]
};

Scenario MakeScenario(const Simulation& sim, int first_sample, int stride,
                      int frames, double scale, const Noise& noise,
                      uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  auto gaussian = [&](double sigma) {
    Eigen::Vector3d e;
    for (int i = 0; i < 3; ++i) e[i] = sigma * normal(rng);
    return e;
  };
  const Eigen::Isometry3d T_b_c = CameraExtrinsic();
  const StampedState& s0 = sim.ground_truth[first_sample];
  const Eigen::Matrix3d R_w_c0 = s0.q_w_b.toRotationMatrix() * T_b_c.linear();
  const Eigen::Matrix3d R_v_w = R_w_c0.transpose();
  const Eigen::Vector3d p_w_c0 = s0.p_w_b + s0.q_w_b * T_b_c.translation();
  Scenario s;
  s.scale = scale;
  s.g_v = R_v_w * Eigen::Vector3d(0.0, 0.0, -sim.options.gravity_m_s2);
  s.b_a = s0.b_a;
  s.b_g = s0.b_g;
  for (int k = 0; k < frames; ++k) {
    const StampedState& t = sim.ground_truth[first_sample + k * stride];
    AlignmentFrame f;
    f.R_v_b =
        R_v_w * t.q_w_b.toRotationMatrix() * Exp(gaussian(noise.rotation_rad));
    const Eigen::Vector3d p_w_c = t.p_w_b + t.q_w_b * T_b_c.translation();
    f.p_v_c = (R_v_w * (p_w_c - p_w_c0) + gaussian(noise.position_m)) / scale;
    s.frames.push_back(f);
    s.v_v.push_back(R_v_w * t.v_w);
    if (k > 0) {
      const int64_t t0 = sim.ground_truth[first_sample + (k - 1) * stride].t_ns;
      s.intervals.emplace_back(t0, t.t_ns, sim.imu, Eigen::Vector3d::Zero(),
                               Eigen::Vector3d::Zero(), sim.options.imu.noise,
                               PreintegrationOptions());
    }
  }
  return s;
}

SimulatorOptions InMotion(bool noise, uint32_t seed) {
  SimulatorOptions o;
  o.seed = seed;
  o.duration_s = 6.0;
  o.motion.still_duration_s = 0.0;
  o.motion.blend_duration_s = 0.0;
  o.motion.start_phase_s = 2.0;
  o.imu.add_noise = noise;
  o.room.landmarks = 10;  // only the IMU and the truth are used
  return o;
}

double AngleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b)) * 180.0 / M_PI;
}

// 11 frames 0.15 s apart (the mono initialiser's default window).
constexpr int kStride = 30;  // IMU samples at 200 Hz
constexpr int kFrames = 11;

TEST(VisualInertialAlignment, NoiseFreeRecoversScaleGravityVelocitiesAndBias) {
  const Simulation sim = Simulate(InMotion(false, 1));
  Scenario s = MakeScenario(sim, 40, kStride, kFrames, 2.5, Noise(), 1);
  const Eigen::Vector3d t_b_c = CameraExtrinsic().translation();
  // The gyroscope bias: the visual rotations are exact, so only the
  // first-order bias correction limits it.
  EXPECT_GT(RotationMisfitRms(s.frames, s.intervals), 1e-3);
  const Eigen::Vector3d b_g = AlignGyroscopeBias(s.frames, s.b_a, &s.intervals);
  EXPECT_LT((b_g - s.b_g).norm(), 1e-6) << b_g.transpose();
  EXPECT_LT(RotationMisfitRms(s.frames, s.intervals), 1e-6);
  // With the true accelerometer bias, the linear system is exact.
  VelocityGravityScale r;
  ASSERT_TRUE(
      SolveVelocityGravityScale(s.frames, s.intervals, t_b_c, s.b_a, true, &r));
  EXPECT_NEAR(r.scale, s.scale, 1e-5 * s.scale);
  EXPECT_LT((r.g_v - s.g_v).norm(), 1e-4);
  for (int k = 0; k < kFrames; ++k) {
    EXPECT_LT((r.v_v[k] - s.v_v[k]).norm(), 1e-5) << k;
  }
  EXPECT_LT(r.scale_sigma, 1e-4 * r.scale);
  // Refining with the magnitude fixed keeps it.
  ASSERT_TRUE(
      RefineGravity(s.frames, s.intervals, t_b_c, s.b_a, 9.81, true, &r));
  EXPECT_NEAR(r.g_v.norm(), 9.81, 1e-12);
  EXPECT_LT(AngleDeg(r.g_v, s.g_v), 1e-3);
  EXPECT_NEAR(r.scale, s.scale, 1e-5 * s.scale);
  // The world it defines: gravity along -z.
  const Eigen::Vector3d g_w = GravityAlignedRotation(r.g_v) * r.g_v;
  EXPECT_LT((g_w - Eigen::Vector3d(0, 0, -9.81)).norm(), 1e-9);
}

TEST(VisualInertialAlignment, MetricTrajectoryGivesVelocityAndGravityOnly) {
  const Simulation sim = Simulate(InMotion(false, 2));
  Scenario s = MakeScenario(sim, 0, 10, 7, 1.0, Noise(), 2);  // 0.3 s stereo
  const Eigen::Vector3d t_b_c = CameraExtrinsic().translation();
  AlignGyroscopeBias(s.frames, s.b_a, &s.intervals);
  VelocityGravityScale r;
  ASSERT_TRUE(SolveVelocityGravityScale(s.frames, s.intervals, t_b_c, s.b_a,
                                        false, &r));
  EXPECT_EQ(r.scale, 1.0);
  EXPECT_LT((r.g_v - s.g_v).norm(), 1e-4);
  EXPECT_LT((r.v_v.back() - s.v_v.back()).norm(), 1e-5);
}

// With the simulator's IMU noise and bias walk and attitudes off by 0.1 deg
// (what a small bundle adjustment leaves), over ten seeds and start times,
// the accelerometer bias known. Gravity and the gyroscope bias meet the
// start's bounds from the alignment alone; the scale, from 1.5 s of gentle
// motion (accelerations ~0.3 m/s^2), comes out within a few percent: the
// white accelerometer noise alone accounts for up to 4 %. The start's 3 %
// is met after the joint adjustment (docs/initialisation.md).
TEST(VisualInertialAlignment, WithNoiseStaysWithinTheStartBounds) {
  const Eigen::Vector3d t_b_c = CameraExtrinsic().translation();
  Noise noise;
  noise.rotation_rad = 0.1 * M_PI / 180.0 / std::sqrt(3.0);
  std::vector<double> scale_errors;
  double worst_gravity = 0.0, worst_bg = 0.0;
  for (uint32_t seed = 1; seed <= 10; ++seed) {
    const Simulation sim = Simulate(InMotion(true, seed));
    Scenario s =
        MakeScenario(sim, 20 * seed, kStride, kFrames, 0.3, noise, seed);
    const Eigen::Vector3d b_g =
        AlignGyroscopeBias(s.frames, s.b_a, &s.intervals);
    VelocityGravityScale r;
    ASSERT_TRUE(SolveVelocityGravityScale(s.frames, s.intervals, t_b_c, s.b_a,
                                          true, &r));
    ASSERT_TRUE(
        RefineGravity(s.frames, s.intervals, t_b_c, s.b_a, 9.81, true, &r));
    scale_errors.push_back(std::abs(r.scale / s.scale - 1.0));
    worst_gravity = std::max(worst_gravity, AngleDeg(r.g_v, s.g_v));
    worst_bg = std::max(worst_bg, (b_g - s.b_g).norm());
  }
  std::sort(scale_errors.begin(), scale_errors.end());
  // Measured: scale median 2.2 %, worst 5.3 %; gravity 0.09 deg; b_g
  // 2.9e-3 rad/s (the 0.1 deg attitude noise over 0.15 s intervals).
  std::printf(
      "alignment with noise, 10 seeds: scale error median %.2f %%, worst "
      "%.2f %%; gravity worst %.3f deg; |db_g| worst %.5f rad/s\n",
      100.0 * scale_errors[5], 100.0 * scale_errors.back(), worst_gravity,
      worst_bg);
  EXPECT_LT(scale_errors[5], 0.03);
  EXPECT_LT(scale_errors.back(), 0.08);
  EXPECT_LT(worst_gravity, 1.0);
  EXPECT_LT(worst_bg, 4e-3);
}

// Why the start does not stop at the linear alignment: noise on the visual
// positions enters the scale's own column (errors in variables), so the
// least-squares scale is biased low, and an unknown accelerometer bias of
// 0.075 m/s^2 moves it by about 10 % on this gentle motion. The joint
// visual-inertial adjustment that follows removes both (docs/
// initialisation.md has the figures).
TEST(VisualInertialAlignment, PositionNoiseAndUnknownAccelBiasBiasTheScale) {
  const Eigen::Vector3d t_b_c = CameraExtrinsic().translation();
  const Simulation sim = Simulate(InMotion(false, 4));
  Noise noise;
  noise.position_m = 0.002;
  double mean_ratio = 0.0;
  for (uint32_t seed = 1; seed <= 5; ++seed) {
    Scenario s = MakeScenario(sim, 40, kStride, kFrames, 0.3, noise, seed);
    AlignGyroscopeBias(s.frames, s.b_a, &s.intervals);
    VelocityGravityScale r;
    ASSERT_TRUE(SolveVelocityGravityScale(s.frames, s.intervals, t_b_c, s.b_a,
                                          true, &r));
    mean_ratio += r.scale / s.scale / 5.0;
  }
  EXPECT_LT(mean_ratio, 0.9) << "2 mm of position noise: biased low";
  Scenario s = MakeScenario(sim, 40, kStride, kFrames, 0.3, Noise(), 1);
  AlignGyroscopeBias(s.frames, Eigen::Vector3d::Zero(), &s.intervals);
  VelocityGravityScale r;
  ASSERT_TRUE(RefineGravity(
      s.frames, s.intervals, t_b_c, Eigen::Vector3d::Zero(), 9.81, true,
      (SolveVelocityGravityScale(s.frames, s.intervals, t_b_c,
                                 Eigen::Vector3d::Zero(), true, &r),
       &r)));
  std::printf(
      "scale ratio with 2 mm position noise %.3f; with b_a unknown "
      "%.3f\n",
      mean_ratio, r.scale / s.scale);
  EXPECT_GT(std::abs(r.scale / s.scale - 1.0), 0.05);
}

TEST(VisualInertialAlignment, TooFewFramesOrNoMotionIsRefused) {
  const Simulation sim = Simulate(InMotion(false, 3));
  Scenario s = MakeScenario(sim, 0, kStride, 1, 1.0, Noise(), 3);
  VelocityGravityScale r;
  EXPECT_FALSE(SolveVelocityGravityScale(s.frames, s.intervals,
                                         Eigen::Vector3d::Zero(),
                                         Eigen::Vector3d::Zero(), true, &r));
  // A visual trajectory that never moves gives no scale column.
  Scenario still = MakeScenario(sim, 0, kStride, 5, 1.0, Noise(), 3);
  for (AlignmentFrame& f : still.frames) f.p_v_c.setZero();
  EXPECT_FALSE(SolveVelocityGravityScale(still.frames, still.intervals,
                                         Eigen::Vector3d::Zero(),
                                         Eigen::Vector3d::Zero(), true, &r));
}

}  // namespace
}  // namespace vio
