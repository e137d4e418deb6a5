#include "estimator/imu_noise_adaptation.h"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <random>
#include <vector>

#include "preintegration/imu_preintegration.h"

namespace vio {
namespace {

constexpr int kP = 0, kTheta = 3, kV = 6;

const ImuNoise kConfigured{1.2e-2, 1.0e-3, 3.0e-3, 1.9393e-5};

// 0.1 s of a turning, accelerating body at 200 Hz, preintegrated with `used`.
PreintegratedImu Interval(const ImuNoise& used) {
  std::vector<ImuSample> samples;
  for (int k = 0; k <= 20; ++k) {
    ImuSample s;
    s.t_ns = k * 5'000'000;
    const double t = 1e-9 * static_cast<double>(s.t_ns);
    s.acc = Eigen::Vector3d(0.5 + t, -0.3, 9.81);
    s.gyr = Eigen::Vector3d(0.2, -0.1 + t, 0.3);
    samples.push_back(s);
  }
  return ImuPreintegration(0, 100'000'000, samples, Eigen::Vector3d::Zero(),
                           Eigen::Vector3d::Zero(), used,
                           PreintegrationOptions())
      .result();
}

// A residual whose accelerometer rows (dp, dv) are k_a L_A u_A and whose
// rotation rows are k_g L_G u_G, L the Cholesky factors of the matching
// covariance blocks: chi^2_A = k_a^2 |u_A|^2, chi^2_G = k_g^2 |u_G|^2.
Vector15d ResidualOfScale(const PreintegratedImu& imu, double k_a, double k_g,
                          const Eigen::Matrix<double, 6, 1>& u_a,
                          const Eigen::Vector3d& u_g) {
  const Matrix15d& s = imu.covariance;
  Eigen::Matrix<double, 6, 6> sigma_a;
  sigma_a << s.block<3, 3>(kP, kP), s.block<3, 3>(kP, kV),
      s.block<3, 3>(kV, kP), s.block<3, 3>(kV, kV);
  const Eigen::Matrix<double, 6, 1> r_a =
      k_a * sigma_a.llt().matrixL().toDenseMatrix() * u_a;
  const Eigen::Vector3d r_g =
      k_g * s.block<3, 3>(kTheta, kTheta).llt().matrixL().toDenseMatrix() * u_g;
  Vector15d r = Vector15d::Zero();
  r.segment<3>(kP) = r_a.head<3>();
  r.segment<3>(kV) = r_a.tail<3>();
  r.segment<3>(kTheta) = r_g;
  // Bias rows: ignored by the estimate, set to something large to show it.
  r.tail<6>().setConstant(1e3);
  return r;
}

ImuNoiseAdaptationOptions Immediate() {
  ImuNoiseAdaptationOptions o;
  o.enabled = true;
  o.smoothing = 1.0;  // each update replaces the average
  return o;
}

TEST(ImuNoiseAdaptation, ResidualsOfKnownScaleGiveThatScale) {
  const PreintegratedImu imu = Interval(kConfigured);
  // |u|^2 = rows: chi^2 / rows = k^2 exactly.
  const Vector15d r =
      ResidualOfScale(imu, 1.7, 0.8, Eigen::Matrix<double, 6, 1>::Ones(),
                      Eigen::Vector3d::Ones());
  ImuChi2Sums sums;
  ASSERT_TRUE(AddImuChi2(r, imu, kConfigured, kConfigured, &sums));
  EXPECT_EQ(sums.accelerometer_rows, 6);
  EXPECT_EQ(sums.gyroscope_rows, 3);
  EXPECT_NEAR(sums.accelerometer / 6.0, 1.7 * 1.7, 1e-9);
  EXPECT_NEAR(sums.gyroscope / 3.0, 0.8 * 0.8, 1e-9);
  ImuNoiseAdaptation adaptation(Immediate());
  adaptation.Update(sums);
  EXPECT_NEAR(adaptation.accelerometer_scale(), 1.7, 1e-9);
  EXPECT_NEAR(adaptation.gyroscope_scale(), 0.8, 1e-9);
  const ImuNoise scaled = adaptation.Scaled(kConfigured);
  EXPECT_NEAR(scaled.accelerometer_noise_density, 1.7 * 1.2e-2, 1e-12);
  EXPECT_NEAR(scaled.gyroscope_noise_density, 0.8 * 1.0e-3, 1e-12);
  EXPECT_EQ(scaled.accelerometer_random_walk,
            kConfigured.accelerometer_random_walk);
  EXPECT_EQ(scaled.gyroscope_random_walk, kConfigured.gyroscope_random_walk);
}

TEST(ImuNoiseAdaptation, IntervalBuiltWithScaledNoiseCountsItsScale) {
  // An interval preintegrated with twice the configured densities whose
  // residual fits that covariance (chi^2 / rows = 1): the sensor's densities
  // are twice the configured ones.
  ImuNoise used = kConfigured;
  used.accelerometer_noise_density *= 2.0;
  used.gyroscope_noise_density *= 2.0;
  const PreintegratedImu imu = Interval(used);
  const Vector15d r =
      ResidualOfScale(imu, 1.0, 1.0, Eigen::Matrix<double, 6, 1>::Ones(),
                      Eigen::Vector3d::Ones());
  ImuChi2Sums sums;
  ASSERT_TRUE(AddImuChi2(r, imu, used, kConfigured, &sums));
  ImuNoiseAdaptation adaptation(Immediate());
  adaptation.Update(sums);
  EXPECT_NEAR(adaptation.accelerometer_scale(), 2.0, 1e-9);
  EXPECT_NEAR(adaptation.gyroscope_scale(), 2.0, 1e-9);
}

TEST(ImuNoiseAdaptation, GaussianResidualsAverageToTheirScale) {
  // Residuals drawn from N(0, k^2 Sigma): the averaged estimate is k within
  // the statistical spread of 400 steps of one interval each.
  const PreintegratedImu imu = Interval(kConfigured);
  std::mt19937 rng(42);
  std::normal_distribution<double> n01;
  ImuNoiseAdaptationOptions options;
  options.enabled = true;
  options.smoothing = 1.0 / 400.0;
  ImuNoiseAdaptation adaptation(options);
  for (int step = 0; step < 4000; ++step) {
    Eigen::Matrix<double, 6, 1> u_a;
    Eigen::Vector3d u_g;
    for (int i = 0; i < 6; ++i) u_a[i] = n01(rng);
    for (int i = 0; i < 3; ++i) u_g[i] = n01(rng);
    ImuChi2Sums sums;
    ASSERT_TRUE(AddImuChi2(ResidualOfScale(imu, 2.5, 0.6, u_a, u_g), imu,
                           kConfigured, kConfigured, &sums));
    adaptation.Update(sums);
  }
  EXPECT_EQ(adaptation.updates(), 4000);
  EXPECT_NEAR(adaptation.accelerometer_scale(), 2.5, 0.1);
  EXPECT_NEAR(adaptation.gyroscope_scale(), 0.6, 0.04);
}

TEST(ImuNoiseAdaptation, ScaleIsClampedAndOffMeansConfigured) {
  const PreintegratedImu imu = Interval(kConfigured);
  const Vector15d r =
      ResidualOfScale(imu, 10.0, 0.1, Eigen::Matrix<double, 6, 1>::Ones(),
                      Eigen::Vector3d::Ones());
  ImuChi2Sums sums;
  ASSERT_TRUE(AddImuChi2(r, imu, kConfigured, kConfigured, &sums));
  ImuNoiseAdaptation adaptation(Immediate());
  adaptation.Update(sums);
  EXPECT_DOUBLE_EQ(adaptation.accelerometer_scale(), 3.0);
  EXPECT_DOUBLE_EQ(adaptation.gyroscope_scale(), 0.5);

  ImuNoiseAdaptationOptions off = Immediate();
  off.enabled = false;
  ImuNoiseAdaptation disabled(off);
  disabled.Update(sums);
  const ImuNoise n = disabled.Scaled(kConfigured);
  EXPECT_EQ(n.accelerometer_noise_density,
            kConfigured.accelerometer_noise_density);
  EXPECT_EQ(n.gyroscope_noise_density, kConfigured.gyroscope_noise_density);
}

TEST(ImuNoiseAdaptation, RejectsNonFiniteResidualAndBadOptions) {
  const PreintegratedImu imu = Interval(kConfigured);
  Vector15d r = Vector15d::Zero();
  r[kV] = std::nan("");
  ImuChi2Sums sums;
  EXPECT_FALSE(AddImuChi2(r, imu, kConfigured, kConfigured, &sums));
  EXPECT_EQ(sums.accelerometer_rows, 0);
  EXPECT_EQ(sums.gyroscope_rows, 0);

  std::string message;
  ImuNoiseAdaptationOptions o;
  o.smoothing = 0.0;
  EXPECT_FALSE(o.Validate(&message));
  EXPECT_EQ(message.rfind("smoothing", 0), 0u);
  o = ImuNoiseAdaptationOptions();
  o.max_scale = 0.9;
  EXPECT_FALSE(o.Validate(&message));
  EXPECT_EQ(message.rfind("max_scale", 0), 0u);
  EXPECT_TRUE(ImuNoiseAdaptationOptions().Validate(&message));
}

}  // namespace
}  // namespace vio
