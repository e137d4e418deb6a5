#include "dataset/imu_curve_residual.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "dataset/sim_trajectory.h"

namespace vio {
namespace {

constexpr double kGravity = 9.81;
const Eigen::Vector3d kGyrBias(0.01, -0.02, 0.005);  // [rad/s]
const Eigen::Vector3d kAccBias(0.1, 0.05, -0.2);     // [m/s^2]

// The simulator's analytic motion (still start, blend, ellipse) sampled at
// 200 Hz over 12 s, fitted by the curve.
TrajectoryCurve FittedMotion(const SimTrajectory& truth) {
  std::vector<StampedPose> poses;
  for (int64_t k = 0; k <= 2400; ++k) {
    const SimState s = truth.At(k * 0.005);
    poses.push_back({k * 5000000, s.p_w_b, s.q_w_b});
  }
  return TrajectoryCurve(poses, CurveFitOptions());
}

// An IMU that felt the analytic motion `offset_s` later than its stamps say
// (sample stamped t: the motion at t + offset_s), with white noise of the
// given densities at 200 Hz and a constant bias.
std::vector<ImuSample> ImuWithOffset(const SimTrajectory& truth,
                                     double offset_s, double acc_density,
                                     double gyr_density) {
  std::mt19937 rng(7);
  std::normal_distribution<double> normal(0.0, 1.0);
  auto gaussian = [&](double sigma) {
    Eigen::Vector3d v;
    for (int i = 0; i < 3; ++i) v(i) = sigma * normal(rng);
    return v;
  };
  const double root_rate = std::sqrt(200.0);
  const Eigen::Vector3d g_w(0.0, 0.0, -kGravity);
  std::vector<ImuSample> imu;
  for (int64_t k = 20; k <= 2380; ++k) {
    const SimState s = truth.At(k * 0.005 + offset_s);
    ImuSample sample;
    sample.t_ns = k * 5000000;
    const Eigen::Vector3d gyr_noise = gaussian(gyr_density * root_rate);
    const Eigen::Vector3d acc_noise = gaussian(acc_density * root_rate);
    sample.gyr = s.w_b + kGyrBias + gyr_noise;
    sample.acc = s.q_w_b.conjugate() * (s.a_w - g_w) + kAccBias + acc_noise;
    imu.push_back(sample);
  }
  return imu;
}

TEST(ImuCurveResidual, FindsTheTimeOffsetOfBothSensors) {
  const SimTrajectory truth{SimMotionOptions()};
  const TrajectoryCurve curve = FittedMotion(truth);
  ImuCurveResidualOptions options;
  options.max_offset_s = 0.03;
  for (const double offset : {-0.0123, 0.0, 0.0071}) {
    const ImuCurveResidual r = CompareImuWithCurve(
        curve, ImuWithOffset(truth, offset, 2e-4, 2e-5), options);
    EXPECT_NEAR(r.gyr_offset_s, offset, 3e-4) << offset;
    EXPECT_NEAR(r.acc_offset_s, offset, 1e-3) << offset;
    // Aligned, the residual is the added noise (2e-5 sqrt(200) rad/s per
    // axis) and the curve's own error; misaligned it is larger.
    EXPECT_LT(r.gyr_rms_at_best.maxCoeff(), 1.5 * 2e-5 * std::sqrt(200.0));
    if (offset != 0.0) {
      EXPECT_GT(r.gyr_rms_at_zero.norm(), 1.5 * r.gyr_rms_at_best.norm());
    }
  }
}

TEST(ImuCurveResidual, AllanDeviationGivesTheWhiteNoiseDensity) {
  const SimTrajectory truth{SimMotionOptions()};
  const TrajectoryCurve curve = FittedMotion(truth);
  const double acc_density = 5e-3, gyr_density = 4e-4;
  const ImuCurveResidual r = CompareImuWithCurve(
      curve, ImuWithOffset(truth, 0.0, acc_density, gyr_density),
      ImuCurveResidualOptions());
  ASSERT_GE(r.allan.size(), 5u);
  // White noise: adev(tau) sqrt(tau) is the density at every tau up to the
  // curve's own error (well below these densities over a second).
  for (const AllanPoint& p : r.allan) {
    if (p.tau_s > 0.25) continue;  // 12 s: too few clusters beyond
    const double root_tau = std::sqrt(p.tau_s);
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(p.gyr(i) * root_tau, gyr_density, 0.15 * gyr_density)
          << "tau " << p.tau_s << " axis " << i;
      EXPECT_NEAR(p.acc(i) * root_tau, acc_density, 0.15 * acc_density)
          << "tau " << p.tau_s << " axis " << i;
    }
  }
  EXPECT_NEAR(r.sample_rate_hz, 200.0, 1e-6);
}

TEST(ImuCurveResidual, RejectsTooFewSamplesAndBadOptions) {
  const SimTrajectory truth{SimMotionOptions()};
  const TrajectoryCurve curve = FittedMotion(truth);
  const std::vector<ImuSample> imu = ImuWithOffset(truth, 0.0, 2e-3, 2e-4);
  const std::vector<ImuSample> few(imu.begin(), imu.begin() + 50);
  EXPECT_THROW(CompareImuWithCurve(curve, few, ImuCurveResidualOptions()),
               std::invalid_argument);
  ImuCurveResidualOptions bad;
  bad.fine_step_s = 0.0;
  EXPECT_THROW(CompareImuWithCurve(curve, imu, bad), std::invalid_argument);
}

}  // namespace
}  // namespace vio
