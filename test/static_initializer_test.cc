#include "estimator/static_initializer.h"

#include <gtest/gtest.h>

#include <random>
#include <string>

#include "dataset/csv.h"
#include "dataset/trajectory_io.h"
#include "geometry/so3.h"

namespace vio {
namespace {

constexpr double kG = 9.81;

// Still IMU readings of a body at attitude q_w_b with the given biases and
// white noise of the given standard deviations, at 200 Hz.
std::vector<ImuSample> StillSamples(const Eigen::Quaterniond& q_w_b,
                                    const Eigen::Vector3d& b_a,
                                    const Eigen::Vector3d& b_g,
                                    double acc_sigma, double gyr_sigma,
                                    double duration_s, std::mt19937* rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  std::vector<ImuSample> out;
  const Eigen::Vector3d f_b = q_w_b.conjugate() * Eigen::Vector3d(0, 0, kG);
  for (int64_t t_ns = 0; t_ns <= static_cast<int64_t>(duration_s * 1e9);
       t_ns += 5000000) {
    ImuSample s;
    s.t_ns = t_ns;
    s.acc = f_b + b_a + acc_sigma * Eigen::Vector3d(n(*rng), n(*rng), n(*rng));
    s.gyr = b_g + gyr_sigma * Eigen::Vector3d(n(*rng), n(*rng), n(*rng));
    out.push_back(s);
  }
  return out;
}

// The angle between the estimated and the true "up" seen from the body [rad]:
// the tilt error, blind to yaw.
double TiltError(const Eigen::Quaterniond& q_est,
                 const Eigen::Quaterniond& q_true) {
  const Eigen::Vector3d up_est = q_est.conjugate() * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d up_true = q_true.conjugate() * Eigen::Vector3d::UnitZ();
  return std::acos(std::min(1.0, up_est.dot(up_true)));
}

TEST(GravityAlignedAttitude, MapsSpecificForceUpWithZeroYaw) {
  std::mt19937 rng(42);
  std::normal_distribution<double> n(0.0, 1.0);
  for (int i = 0; i < 50; ++i) {
    const Eigen::Vector3d f_b(n(rng), n(rng), n(rng));
    const Eigen::Quaterniond q = GravityAlignedAttitude(f_b);
    EXPECT_NEAR((q * f_b.normalized() - Eigen::Vector3d::UnitZ()).norm(), 0.0,
                1e-12);
    EXPECT_NEAR(Yaw(q.toRotationMatrix()), 0.0, 1e-12);
  }
  EXPECT_THROW(GravityAlignedAttitude(Eigen::Vector3d::Zero()),
               std::invalid_argument);
}

TEST(StaticInitializer, RecoversTiltAndGyroBiasFromSyntheticStillData) {
  std::mt19937 rng(7);
  const Eigen::Quaterniond q_true =
      ExpQuaternion(Eigen::Vector3d(0.3, -0.2, 1.1));
  const Eigen::Vector3d b_g(0.01, -0.02, 0.005);
  StaticInitOptions options;
  StaticInitializer init(options, kG);
  for (const ImuSample& s : StillSamples(q_true, Eigen::Vector3d::Zero(), b_g,
                                         0.02, 0.002, 1.5, &rng)) {
    init.AddSample(s);
  }
  StaticInitState state;
  ASSERT_TRUE(init.TryInitialize(&state));
  // 200 samples with sigma 0.02 m/s^2: the mean is good to ~1.4e-3 m/s^2,
  // i.e. ~1.5e-4 rad of tilt; the gyro mean to ~1.4e-4 rad/s.
  EXPECT_LT(TiltError(state.q_w_b, q_true), 1e-3);
  EXPECT_LT((state.b_g - b_g).norm(), 1e-3);
  EXPECT_NEAR(Yaw(state.q_w_b.toRotationMatrix()), 0.0, 1e-12);
  EXPECT_EQ(state.b_a, Eigen::Vector3d::Zero());
}

TEST(StaticInitializer, EstimatesAccelBiasAlongGravityWhenAsked) {
  std::mt19937 rng(8);
  const Eigen::Quaterniond q_true = ExpQuaternion(Eigen::Vector3d(0.1, 0.2, 0));
  const Eigen::Vector3d up_b = q_true.conjugate() * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d b_a = 0.08 * up_b;
  StaticInitOptions options;
  options.estimate_accel_bias = true;
  StaticInitializer init(options, kG);
  for (const ImuSample& s : StillSamples(q_true, b_a, Eigen::Vector3d::Zero(),
                                         0.01, 0.001, 1.2, &rng)) {
    init.AddSample(s);
  }
  StaticInitState state;
  ASSERT_TRUE(init.TryInitialize(&state));
  EXPECT_LT((state.b_a - b_a).norm(), 2e-3);
}

TEST(StaticInitializer, RefusesWhileMovingOrBeforeTheWindowIsFull) {
  std::mt19937 rng(9);
  StaticInitOptions options;
  StaticInitializer init(options, kG);
  const auto samples =
      StillSamples(Eigen::Quaterniond::Identity(), Eigen::Vector3d::Zero(),
                   Eigen::Vector3d::Zero(), 0.01, 0.001, 1.5, &rng);
  StaticInitState state;
  for (size_t i = 0; i < 100; ++i) init.AddSample(samples[i]);
  EXPECT_FALSE(init.TryInitialize(&state));  // 0.5 s of 1 s
  // A vehicle rocking to and fro: +-1 m/s^2, a 0.5 s period.
  init.Clear();
  for (size_t i = 0; i < samples.size(); ++i) {
    ImuSample s = samples[i];
    s.acc.x() += (i % 100 < 50) ? 1.0 : -1.0;
    init.AddSample(s);
  }
  EXPECT_FALSE(init.TryInitialize(&state));
}

// EuRoC V1_01_easy: the MAV stands on the ground for the first ~5 s. Its
// ground truth carries the biases (estimated by the dataset's authors), so the
// gyroscope mean must reproduce b_g and the gravity direction the true tilt.
TEST(StaticInitializer, MatchesGroundTruthOnRealStillEurocImu) {
  const std::string root =
      std::string(VIO_SHARED_DIR) + "/data/euroc_V1_01_first5s/mav0/";
  const std::vector<StampedState> truth =
      ReadEurocGroundTruth(root + "state_groundtruth_estimate0/data.csv");
  const int64_t t0 = truth.front().t_ns;
  StaticInitOptions options;
  options.window_s = 4.0;
  StaticInitializer init(options, kG);
  CsvReader csv(root + "imu0/data.csv");
  while (csv.Next()) {
    ImuSample s;
    s.t_ns = csv.Int64(0);
    if (s.t_ns < t0) continue;
    if (s.t_ns > t0 + 4000000000LL) break;
    s.gyr = {csv.Double(1), csv.Double(2), csv.Double(3)};
    s.acc = {csv.Double(4), csv.Double(5), csv.Double(6)};
    init.AddSample(s);
  }
  StaticInitState state;
  ASSERT_TRUE(init.TryInitialize(&state)) << "the first 4 s are still";
  // The ground truth covers the whole flight: take its state mid-span.
  size_t mid = 0;
  while (truth[mid].t_ns < t0 + 2000000000LL) ++mid;
  const StampedState& gt = truth[mid];
  // Measured: (2.3e-4, 6.7e-4, 1.15e-3) rad/s off the ground truth's b_g of
  // (-0.0023, 0.0215, 0.0770), which is itself an estimate; white noise alone
  // averages to 1.7e-4 / sqrt(4 s) = 8.5e-5 rad/s. 2e-3 rad/s is 2.6 % of
  // |b_g|: an estimator that ignored the bias would miss by 0.077.
  EXPECT_LT((state.b_g - gt.b_g).cwiseAbs().maxCoeff(), 2e-3)
      << "estimate " << state.b_g.transpose() << " truth "
      << gt.b_g.transpose();
  // Tilt: without b_a the estimate is off by up to |b_a| / g = 7.6 mrad
  // (measured 4 mrad with the truth's b_a removed from the mean).
  EXPECT_LT(TiltError(state.q_w_b, gt.q_w_b), 0.01)
      << "tilt error " << TiltError(state.q_w_b, gt.q_w_b) << " rad";
}

}  // namespace
}  // namespace vio
