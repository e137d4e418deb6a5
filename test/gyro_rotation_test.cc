#include "preintegration/gyro_rotation.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "geometry/so3.h"
#include "preintegration/imu_preintegration.h"
#include "test/testing/analytic_trajectory.h"
#include "test/testing/jacobian_test_utils.h"

namespace vio {
namespace {

using testing::AnalyticTrajectory;
using testing::ExpectJacobianNear;

constexpr int64_t kPeriodNs = 5000000;  // 200 Hz
constexpr double kMaxGap = 0.02;        // [s]
const Eigen::Vector3d kBa(0.12, -0.05, 0.2);
const Eigen::Vector3d kBg(0.01, -0.02, 0.005);

class GyroRotationOnTrajectory : public ::testing::Test {
 protected:
  const AnalyticTrajectory traj_;
  const std::vector<ImuSample> samples_ =
      traj_.Samples(0, 3000000000, kPeriodNs, kBa, kBg);
  // Off the sample grid, one end on a sample, two equal end stamps, and
  // ends closer to each other than a sample period.
  const int64_t t0_ns_ = 300000000 + 1234567;
  const std::vector<int64_t> ends_ns_ = {
      t0_ns_ + 1000000,   t0_ns_ + 3500000,  t0_ns_ + 50000000,
      400000000,          400000000,         t0_ns_ + 150003000,
      t0_ns_ + 700000000, t0_ns_ + 1999000000};
};

TEST_F(GyroRotationOnTrajectory, MatchesFullPreintegrationAtEveryEnd) {
  const Eigen::Vector3d b_g(0.03, -0.01, 0.02);
  const std::vector<GyroRotation> rotations =
      IntegrateGyroRotations(t0_ns_, ends_ns_, samples_, b_g, kMaxGap);
  ASSERT_EQ(rotations.size(), ends_ns_.size());
  PreintegrationOptions options;
  options.max_sample_gap = kMaxGap;
  for (size_t k = 0; k < ends_ns_.size(); ++k) {
    SCOPED_TRACE("end " + std::to_string(ends_ns_[k]));
    const PreintegratedImu full =
        ImuPreintegration(t0_ns_, ends_ns_[k], samples_, kBa, b_g, ImuNoise(),
                          options)
            .result();
    const GyroRotation& r = rotations[k];
    EXPECT_EQ(r.t0_ns, t0_ns_);
    EXPECT_EQ(r.t1_ns, ends_ns_[k]);
    EXPECT_EQ(r.lin_b_g, b_g);
    // The same steps in the same order: the rotation bit for bit, its
    // Jacobian up to the rounding of the full 15 x 15 product's sums.
    EXPECT_EQ(full.delta.q.coeffs(), r.delta_q.coeffs());
    EXPECT_LT((full.d_dq_d_bg - r.d_dq_d_bg).cwiseAbs().maxCoeff(), 1e-14);
    // And the bias-corrected rotation too, away from the linearisation.
    const Eigen::Vector3d other = b_g + Eigen::Vector3d(-0.02, 0.01, 0.03);
    EXPECT_LT(
        Log(full.Corrected(kBa, other).q.conjugate() * r.Corrected(other))
            .norm(),
        1e-14);
  }
}

TEST_F(GyroRotationOnTrajectory, NoiseFreeRotationMatchesTruth) {
  const std::vector<GyroRotation> rotations =
      IntegrateGyroRotations(t0_ns_, ends_ns_, samples_, kBg, kMaxGap);
  const Eigen::Quaterniond q0 = traj_.Rotation(1e-9 * t0_ns_);
  for (size_t k = 0; k < ends_ns_.size(); ++k) {
    const Eigen::Quaterniond truth =
        q0.conjugate() * traj_.Rotation(1e-9 * ends_ns_[k]);
    // The midpoint scheme's discretisation at 200 Hz over up to 2 s.
    EXPECT_LT(Log(truth.conjugate() * rotations[k].delta_q).norm(), 1e-4)
        << "end " << ends_ns_[k];
  }
}

TEST_F(GyroRotationOnTrajectory, BiasJacobianMatchesReintegration) {
  const std::vector<int64_t> end = {ends_ns_.back()};
  const GyroRotation r =
      IntegrateGyroRotations(t0_ns_, end, samples_, kBg, kMaxGap).front();
  const auto reintegrated = [&](const Eigen::VectorXd& db) -> Eigen::VectorXd {
    const GyroRotation p = IntegrateGyroRotations(
                               t0_ns_, end, samples_, kBg + db, kMaxGap)
                               .front();
    return Log(r.delta_q.conjugate() * p.delta_q);
  };
  ExpectJacobianNear("d dq / d b_g", r.d_dq_d_bg, reintegrated,
                     Eigen::VectorXd::Zero(3), 1e-6, 1e-5);
}

TEST_F(GyroRotationOnTrajectory, RejectsEndsOutOfOrderNamingTheStamps) {
  try {
    IntegrateGyroRotations(t0_ns_, {t0_ns_ + 20000000, t0_ns_ + 10000000},
                           samples_, kBg, kMaxGap);
    FAIL() << "expected ImuError";
  } catch (const ImuError& e) {
    EXPECT_NE(std::string(e.what()).find(std::to_string(t0_ns_ + 10000000)),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(
      IntegrateGyroRotations(t0_ns_, {t0_ns_}, samples_, kBg, kMaxGap),
      ImuError);
  EXPECT_TRUE(
      IntegrateGyroRotations(t0_ns_, {}, samples_, kBg, kMaxGap).empty());
}

TEST_F(GyroRotationOnTrajectory, RejectsAGapAsThePreintegrationDoes) {
  std::vector<ImuSample> gappy = samples_;
  gappy.erase(gappy.begin() + 150, gappy.begin() + 160);  // 55 ms missing
  try {
    IntegrateGyroRotations(t0_ns_, ends_ns_, gappy, kBg, kMaxGap);
    FAIL() << "expected ImuError";
  } catch (const ImuError& e) {
    EXPECT_NE(std::string(e.what()).find("max_sample_gap"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace vio
