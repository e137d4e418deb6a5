#include "dataset/trajectory_curve.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

#include "dataset/sim_trajectory.h"
#include "dataset/trajectory_io.h"
#include "geometry/so3.h"

namespace vio {
namespace {

std::vector<StampedState> GroundTruth(const std::string& sequence) {
  return ReadEurocGroundTruth(std::string(VIO_SHARED_DIR) + "/data/" +
                              sequence +
                              "/mav0/state_groundtruth_estimate0/data.csv");
}

std::vector<StampedPose> Poses(const std::vector<StampedState>& states) {
  std::vector<StampedPose> poses;
  for (const StampedState& s : states) poses.push_back(PoseOf(s));
  return poses;
}

double Seconds(int64_t t_ns, const TrajectoryCurve& curve) {
  return static_cast<double>(t_ns - curve.start_ns()) * 1e-9;
}

// RMS of |curve velocity - recorded velocity| over the samples [m/s].
double VelocityRms(const TrajectoryCurve& curve,
                   const std::vector<StampedState>& states) {
  double sum = 0.0;
  for (const StampedState& s : states) {
    sum += (curve.At(Seconds(s.t_ns, curve)).v_w - s.v_w).squaredNorm();
  }
  return std::sqrt(sum / states.size());
}

// 12 s of the simulator's motion (still start, blend, ellipse) sampled at
// 200 Hz, with `noise` [m] and [rad] per axis.
std::vector<StampedPose> SampledMotion(const SimTrajectory& truth,
                                       double noise) {
  std::mt19937 rng(42);
  std::normal_distribution<double> normal(0.0, noise);
  auto gaussian = [&] {
    const double x = normal(rng), y = normal(rng), z = normal(rng);
    return Eigen::Vector3d(x, y, z);
  };
  std::vector<StampedPose> poses;
  for (int64_t k = 0; k <= 2400; ++k) {
    const SimState s = truth.At(k * 0.005);
    poses.push_back({k * 5000000, s.p_w_b + gaussian(),
                     s.q_w_b * ExpQuaternion(gaussian())});
  }
  return poses;
}

// RMS errors of the curve against the truth over its inner span.
struct Errors {
  double p = 0, v = 0, a = 0, r = 0, w = 0;
};

Errors Compare(const TrajectoryCurve& curve, const SimTrajectory& truth) {
  Errors e;
  int n = 0;
  for (double t = 0.1; t < 11.9; t += 0.01, ++n) {
    const SimState x = curve.At(t), s = truth.At(t);
    e.p += (x.p_w_b - s.p_w_b).squaredNorm();
    e.v += (x.v_w - s.v_w).squaredNorm();
    e.a += (x.a_w - s.a_w).squaredNorm();
    e.r += Log(s.q_w_b.conjugate() * x.q_w_b).squaredNorm();
    e.w += (x.w_b - s.w_b).squaredNorm();
  }
  for (double* x : {&e.p, &e.v, &e.a, &e.r, &e.w}) *x = std::sqrt(*x / n);
  return e;
}

TEST(TrajectoryCurve, RecoversAnAnalyticMotionAndItsDerivatives) {
  const SimTrajectory truth{SimMotionOptions()};
  const TrajectoryCurve curve(SampledMotion(truth, 0.0), CurveFitOptions());
  EXPECT_LT(curve.report().position_max_m, 1e-5);
  EXPECT_LT(curve.report().rotation_max_rad, 1e-5);
  const Errors e = Compare(curve, truth);
  EXPECT_LT(e.p, 1e-5);  // [m]
  EXPECT_LT(e.r, 1e-5);  // [rad]
  EXPECT_LT(e.v, 1e-3);  // [m/s]
  EXPECT_LT(e.w, 1e-3);  // [rad/s]
  EXPECT_LT(e.a, 0.05);  // [m/s^2]
}

TEST(TrajectoryCurve, FollowsTheMotionNotTheNoise) {
  // With 1 mm / 1 mrad of noise per axis (1.7 mm, 1.7 mrad in norm) the
  // curve is closer to the truth than the samples are.
  const SimTrajectory truth{SimMotionOptions()};
  const TrajectoryCurve curve(SampledMotion(truth, 1e-3), CurveFitOptions());
  EXPECT_NEAR(curve.report().position_rms_m, std::sqrt(3.0) * 1e-3, 2e-4);
  EXPECT_NEAR(curve.report().rotation_rms_rad, std::sqrt(3.0) * 1e-3, 2e-4);
  const Errors e = Compare(curve, truth);
  EXPECT_LT(e.p, 0.7e-3);  // [m]
  EXPECT_LT(e.r, 0.7e-3);  // [rad]
}

TEST(TrajectoryCurve, PassesThroughEurocMh05GroundTruthWithinItsNoise) {
  // 113 s of real MAV flight at 200 Hz (Leica position, mm noise).
  const std::vector<StampedState> states = GroundTruth("euroc_MH_05_imu_gt");
  const TrajectoryCurve curve(Poses(states), CurveFitOptions());
  const CurveFitReport& r = curve.report();
  EXPECT_EQ(r.samples, static_cast<int>(states.size()));
  EXPECT_LT(r.position_rms_m, 1e-3);
  EXPECT_LT(r.rotation_rms_rad, 1e-3);
  // The worst sample is a 10 m/s^2 jolt at 79.3 s that 0.05 s knots smooth.
  EXPECT_LT(r.position_max_m, 0.03);
  // The recorded velocity (from EuRoC's own estimator, never fitted here)
  // agrees with the curve's derivative.
  EXPECT_LT(VelocityRms(curve, states), 0.05);
}

TEST(TrajectoryCurve, FitsRotationsWithTheirOwnKnotSpacing) {
  // MH_05's attitude (EuRoC's estimate, with the IMU) has content that
  // 0.05 s knots smooth; rotation knots 0.0125 s apart follow it while the
  // positions keep their 0.05 s spline. 20 s of the flight (30 to 50 s in),
  // to keep the test fast.
  const std::vector<StampedState> all = GroundTruth("euroc_MH_05_imu_gt");
  ASSERT_GT(all.size(), 10000u);
  const std::vector<StampedState> states(all.begin() + 6000,
                                         all.begin() + 10000);
  CurveFitOptions options;
  const TrajectoryCurve coarse(Poses(states), options);
  options.rotation_knot_spacing_s = 0.0125;
  const TrajectoryCurve fine(Poses(states), options);
  ASSERT_NE(fine.rotation_spline(), nullptr);
  EXPECT_EQ(coarse.rotation_spline(), nullptr);
  EXPECT_LT(fine.report().rotation_rms_rad,
            0.2 * coarse.report().rotation_rms_rad);
  EXPECT_LT(fine.report().rotation_max_rad, 2e-3);
  EXPECT_DOUBLE_EQ(fine.report().position_rms_m,
                   coarse.report().position_rms_m);
  for (const double t : {1.0, 7.3, 15.0}) {
    const SimState a = coarse.At(t);
    const SimState b = fine.At(t);
    EXPECT_EQ(a.p_w_b, b.p_w_b);
    EXPECT_EQ(a.a_w, b.a_w);
    // The fine rotation is that of its own spline, evaluated at t.
    const PoseSplineState r = fine.rotation_spline()->Evaluate(t);
    EXPECT_EQ(b.w_b, r.w);
    EXPECT_LT(Log(a.q_w_b.conjugate() * b.q_w_b).norm(), 0.02);
  }
  options.rotation_knot_spacing_s = -0.01;
  EXPECT_THROW(TrajectoryCurve(Poses(states), options),
               std::invalid_argument);
}

TEST(TrajectoryCurve, InterpolatesTheTwentyHertzV101GroundTruth) {
  // The whole V1_01 ground truth, 145 s at 20 Hz: one sample per knot.
  const std::vector<StampedState> states = GroundTruth("euroc_V1_01_first5s");
  const TrajectoryCurve curve(Poses(states), CurveFitOptions());
  EXPECT_LT(curve.report().position_rms_m, 1e-4);
  EXPECT_LT(curve.report().rotation_rms_rad, 1e-4);
  EXPECT_LT(VelocityRms(curve, states), 0.01);
  EXPECT_NEAR(curve.duration_s(), 144.70, 1e-6);
}

TEST(TrajectoryCurve, RejectsTooFewOrUnorderedPoses) {
  std::vector<StampedPose> poses(1);
  EXPECT_THROW(TrajectoryCurve(poses, CurveFitOptions()),
               std::invalid_argument);
  poses.resize(3);
  poses[1].t_ns = 100000000;
  poses[2].t_ns = 100000000;
  try {
    const TrajectoryCurve curve(poses, CurveFitOptions());
    ADD_FAILURE() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("stamps must increase"),
              std::string::npos)
        << e.what();
  }
  poses[2].t_ns = 200000000;
  CurveFitOptions bad;
  bad.knot_spacing_s = 0.0;
  EXPECT_THROW(TrajectoryCurve(poses, bad), std::invalid_argument);
  const TrajectoryCurve curve(poses, CurveFitOptions());
  EXPECT_THROW(curve.At(0.3), std::out_of_range);
}

}  // namespace
}  // namespace vio
