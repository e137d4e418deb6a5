// Preintegration on real data: EuRoC MH_05_difficult's ADIS16448 IMU against
// its 200 Hz ground truth (position, orientation, velocity, biases) while the
// MAV flies. imu0's T_BS is the identity, so the ground-truth body frame is
// the IMU frame. (EuRoC's ground truth was itself fitted with this IMU, so
// this is a consistency check, not an independent truth; shared/data/README.)

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <string>
#include <vector>

#include "dataset/euroc_reader.h"
#include "dataset/trajectory_io.h"
#include "factors/imu_factor.h"
#include "geometry/so3.h"
#include "preintegration/imu_preintegration.h"

namespace vio {
namespace {

const std::string kDir =
    std::string(VIO_SHARED_DIR) + "/data/euroc_MH_05_imu_gt/mav0/";
constexpr double kGravity = 9.81;

std::vector<double> Pose(const StampedState& s) {
  return {s.p_w_b.x(), s.p_w_b.y(), s.p_w_b.z(), s.q_w_b.x(),
          s.q_w_b.y(), s.q_w_b.z(), s.q_w_b.w()};
}

std::vector<double> SpeedBias(const StampedState& s) {
  return {s.v_w.x(), s.v_w.y(), s.v_w.z(), s.b_a.x(), s.b_a.y(),
          s.b_a.z(), s.b_g.x(), s.b_g.y(), s.b_g.z()};
}

struct IntervalResult {
  Vector15d r;  // unweighted residual at the ground-truth states
  Eigen::Matrix<double, 5, 1> block_chi2;  // r_k^T P_kk^-1 r_k per 3-block
};

// Intervals of 0.5 s (100 ground-truth steps) starting every 211 steps
// (about 1 s): 105 intervals spread over the whole flight.
constexpr size_t kLength = 100;
constexpr size_t kStride = 211;

class EurocImu : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    imu_ = new std::vector<ImuSample>(ReadEurocImu(kDir + "imu0/data.csv"));
    gt_ = new std::vector<StampedState>(
        ReadEurocGroundTruth(kDir + "state_groundtruth_estimate0/data.csv"));
  }
  static void TearDownTestSuite() {
    delete imu_;
    delete gt_;
  }

  // The IMU factor's residual between the ground-truth states gt[i] and
  // gt[i + kLength], preintegrated at the ground-truth biases of gt[i]
  // (or, with zero_bias, ignoring the biases altogether).
  static IntervalResult Evaluate(size_t i, bool zero_bias = false) {
    StampedState a = (*gt_)[i];
    StampedState b = (*gt_)[i + kLength];
    if (zero_bias) {
      a.b_a.setZero();
      a.b_g.setZero();
      b.b_a.setZero();
      b.b_g.setZero();
    }
    const ImuPreintegration pre(a.t_ns, b.t_ns, *imu_, a.b_a, a.b_g, ImuNoise(),
                                PreintegrationOptions());
    const ImuFactor factor(pre.result(), kGravity);
    const std::vector<double> pose_i = Pose(a), sb_i = SpeedBias(a);
    const std::vector<double> pose_j = Pose(b), sb_j = SpeedBias(b);
    const double* params[] = {pose_i.data(), sb_i.data(), pose_j.data(),
                              sb_j.data()};
    IntervalResult out;
    EXPECT_TRUE(factor.UnweightedResidual(params, &out.r));
    const Matrix15d& P = pre.covariance();
    for (int k = 0; k < 5; ++k) {
      const Eigen::Vector3d r_k = out.r.segment<3>(3 * k);
      out.block_chi2[k] = r_k.dot(P.block<3, 3>(3 * k, 3 * k).llt().solve(r_k));
    }
    return out;
  }

  static std::vector<IntervalResult> EvaluateAll(bool zero_bias = false) {
    std::vector<IntervalResult> out;
    for (size_t i = 100; i + kLength < gt_->size(); i += kStride) {
      out.push_back(Evaluate(i, zero_bias));
    }
    return out;
  }

  // Root mean square of |r| over the intervals for the 3-block at `slot`.
  static double Rms(const std::vector<IntervalResult>& results, int slot) {
    double sum = 0.0;
    for (const auto& r : results) sum += r.r.segment<3>(slot).squaredNorm();
    return std::sqrt(sum / results.size());
  }

  static double MeanBlockChi2(const std::vector<IntervalResult>& results,
                              int block) {
    double sum = 0.0;
    for (const auto& r : results) sum += r.block_chi2[block];
    return sum / results.size();
  }

  static std::vector<ImuSample>* imu_;
  static std::vector<StampedState>* gt_;
};

std::vector<ImuSample>* EurocImu::imu_ = nullptr;
std::vector<StampedState>* EurocImu::gt_ = nullptr;

TEST_F(EurocImu, RotationResidualHasTheSizeTheGyroNoiseClaims) {
  // r_th ~ N(0, P_th) makes r^T P_th^-1 r chi-squared with 3 degrees of
  // freedom: mean 3, and over 105 intervals the mean's standard deviation is
  // sqrt(6 / 105) = 0.24. Measured: 2.03 (the ground truth was fitted with
  // this IMU, which pulls the residual below an independent truth's). The
  // test asks for agreement within a factor 2 of variance either way,
  // [1.5, 6]; a unit mistake (a density used as a per-sample sigma: a factor
  // 200 in variance) or a dropped or sign-flipped bias (mean > 1000, see
  // below) leaves it.
  const std::vector<IntervalResult> results = EvaluateAll();
  ASSERT_EQ(results.size(), 105u);
  const double mean = MeanBlockChi2(results, kImuR / 3);
  EXPECT_GT(mean, 1.5);
  EXPECT_LT(mean, 6.0);
  for (const auto& r : results) EXPECT_LT(r.r.segment<3>(kImuR).norm(), 1e-3);
}

TEST_F(EurocImu, GroundTruthBiasesMakeThePredictedMotionMatch) {
  // Preintegrated with the ground-truth biases, the predicted relative motion
  // over 0.5 s matches the ground truth to (measured rms) 1.7e-4 rad,
  // 0.036 m/s and 0.012 m; ignoring the biases gives 0.040 rad, 0.16 m/s and
  // 0.033 m. The bounds below sit between the two, so a dropped or
  // sign-flipped bias fails.
  const std::vector<IntervalResult> with_bias = EvaluateAll();
  const std::vector<IntervalResult> without_bias = EvaluateAll(true);
  EXPECT_LT(Rms(with_bias, kImuR), 1e-3);
  EXPECT_LT(Rms(with_bias, kImuV), 0.05);
  EXPECT_LT(Rms(with_bias, kImuP), 0.02);
  EXPECT_GT(Rms(without_bias, kImuR), 20 * Rms(with_bias, kImuR));
  EXPECT_GT(Rms(without_bias, kImuV), 2 * Rms(with_bias, kImuV));
  EXPECT_GT(Rms(without_bias, kImuP), 2 * Rms(with_bias, kImuP));
}

TEST_F(EurocImu, VelocityResidualExceedsTheDatasheetAccelerometerNoise) {
  // What does not hold: with the datasheet accelerometer density (2e-3
  // m/s^2/sqrt(Hz), imu0/sensor.yaml) the velocity and position blocks'
  // mean chi-squared is about 520 and 820 instead of 3 (measured), 13x and
  // 17x in standard deviation. The ground truth's own p and v agree to
  // 4.6 mm rms over 0.5 s, below the 12 mm position residual, so the excess
  // is what the flying MAV's accelerometer senses (vibration) and the
  // smoothed truth does not hold: an estimator needs an inflated density
  // (OKVIS and VINS-Mono use 0.08 for EuRoC). This pins the measured fact so
  // that the statement in docs/preintegration.md stays true.
  const std::vector<IntervalResult> results = EvaluateAll();
  EXPECT_GT(MeanBlockChi2(results, kImuV / 3), 30.0);
  EXPECT_GT(MeanBlockChi2(results, kImuP / 3), 30.0);
}

TEST_F(EurocImu, BiasCorrectionAgreesWithReintegrationOnRealData) {
  // Linearised off the ground-truth biases and corrected back to them, the
  // first-order terms agree with re-integration up to a second-order
  // remainder: within the default re-propagation thresholds (offsets of
  // 0.09 m/s^2 and 0.009 rad/s) it is a small fraction of the change it
  // corrects and far inside the residuals above (0.036 m/s, 0.012 m rms).
  const StampedState& a = (*gt_)[5000];
  const StampedState& b = (*gt_)[5000 + kLength];
  const Eigen::Vector3d off_a = Eigen::Vector3d(0.09, 0.0, 0.0);
  const Eigen::Vector3d off_g = Eigen::Vector3d(0.0, 0.009, 0.0);
  const ImuPreintegration off(a.t_ns, b.t_ns, *imu_, a.b_a + off_a,
                              a.b_g + off_g, ImuNoise(),
                              PreintegrationOptions());
  ASSERT_FALSE(off.NeedsRepropagation(a.b_a, a.b_g));
  const ImuPreintegration at_truth(a.t_ns, b.t_ns, *imu_, a.b_a, a.b_g,
                                   ImuNoise(), PreintegrationOptions());
  const ImuDelta corrected = off.Corrected(a.b_a, a.b_g);
  const ImuDelta& exact = at_truth.delta();
  const double theta_change = Log(exact.q.conjugate() * off.delta().q).norm();
  const double v_change = (exact.v - off.delta().v).norm();
  const double p_change = (exact.p - off.delta().p).norm();
  const double theta_error = Log(exact.q.conjugate() * corrected.q).norm();
  const double v_error = (exact.v - corrected.v).norm();
  const double p_error = (exact.p - corrected.p).norm();
  // Measured: changes 4.5e-3 rad, 0.042 m/s, 0.011 m; remainders 2.6e-8 rad,
  // 9.7e-5 m/s, 1.6e-5 m.
  EXPECT_LT(theta_error, 0.01 * theta_change);
  EXPECT_LT(v_error, 0.01 * v_change);
  EXPECT_LT(p_error, 0.01 * p_change);
  EXPECT_LT(v_error, 1e-3);
  EXPECT_LT(p_error, 1e-4);
}

}  // namespace
}  // namespace vio
