// The release of orphan world points (estimator/point_release.h), the path
// of Estimator::ReleaseOrphanPoints: on a hand-made prior over a pose, a
// speed-bias block and world points, against the Schur complement and the
// minimisation over the point computed here with Eigen.

#include "estimator/point_release.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <vector>

#include "estimator/feature_manager.h"
#include "factors/marginalization_prior.h"
#include "geometry/feature_observation.h"

namespace vio {
namespace {

// Landmark ids: two world points and an ordinary landmark.
constexpr int64_t kPointA = 1, kPointB = 2, kOrdinary = 3;
// Tangent layout of the prior [pose 6 | speed-bias 9 | A 3 | B 3].
constexpr int kPose = 0, kSpeedBias = 6, kA = 15, kB = 18, kDim = 21;

class PointRelease : public ::testing::Test {
 protected:
  void SetUp() override {
    std::vector<FeatureObservation> obs(3);
    for (int i = 0; i < 3; ++i) obs[i].feature_id = i + 1;
    features_.AddFrame(0, obs);
    for (const int64_t id : {kPointA, kPointB}) {
      Landmark& l = features_.landmarks().at(id);
      l.world_point = true;
      l.p_w = {0.5 * static_cast<double>(id), -0.2, 4.0 + id};
      l.p_w_first = l.p_w;
    }
    const Eigen::Quaterniond q = Eigen::Quaterniond(
        Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()));
    pose_ = {1.0, -2.0, 0.5, q.x(), q.y(), q.z(), q.w()};
    for (int i = 0; i < 9; ++i) speed_bias_[i] = 0.1 * (i + 1);

    // A full-rank square root with every block coupled to every other.
    std::mt19937 rng(42);
    std::normal_distribution<double> n(0.0, 1.0);
    J_.resize(kDim, kDim);
    r0_.resize(kDim);
    for (int i = 0; i < kDim; ++i) {
      r0_[i] = n(rng);
      for (int j = 0; j < kDim; ++j) J_(i, j) = n(rng);
      J_(i, i) += 6.0;
    }
    blocks_ = {pose_.data(), speed_bias_.data(), P(kPointA), P(kPointB)};
    prior_ = MakeFullPrior();
  }

  double* P(int64_t id) { return features_.landmarks().at(id).p_w.data(); }

  // The prior over blocks_ with x0 = the current values.
  std::unique_ptr<MarginalizationPrior> MakeFullPrior() {
    std::vector<PriorBlock> b(4);
    b[0].kind = PriorBlockKind::kPose;
    b[0].x0.assign(pose_.begin(), pose_.end());
    b[1].x0.assign(speed_bias_.begin(), speed_bias_.end());
    b[2].x0.assign(P(kPointA), P(kPointA) + 3);
    b[3].x0.assign(P(kPointB), P(kPointB) + 3);
    return std::make_unique<MarginalizationPrior>(b, J_, r0_);
  }

  // 1/2 |r|^2 of `prior` at the values of `blocks`.
  static double Cost(const MarginalizationPrior& prior,
                     const std::vector<double*>& blocks,
                     Eigen::VectorXd* residual = nullptr) {
    Eigen::VectorXd r(prior.num_residuals());
    std::vector<const double*> params(blocks.begin(), blocks.end());
    EXPECT_TRUE(prior.Evaluate(params.data(), r.data(), nullptr));
    if (residual) *residual = r;
    return 0.5 * r.squaredNorm();
  }

  // The orphan: its last sighting removed as an outlier would be.
  void Orphan(int64_t id) { features_.RemoveSighting(id, 0, 0); }

  std::array<double, 7> pose_{};
  std::array<double, 9> speed_bias_{};
  FeatureManager features_{1};
  Eigen::MatrixXd J_;
  Eigen::VectorXd r0_;
  std::vector<double*> blocks_;
  std::unique_ptr<MarginalizationPrior> prior_;
};

// The rows/columns of the full tangent vector without [m, m + 3).
Eigen::MatrixXd Without(const Eigen::MatrixXd& M, int m) {
  const int n = static_cast<int>(M.rows()) - 3;
  Eigen::MatrixXd out(n, M.cols());
  out << M.topRows(m), M.bottomRows(M.rows() - m - 3);
  return out;
}

TEST_F(PointRelease, ForgetsTheOrphanAndShrinksThePriorByItsBlock) {
  Orphan(kPointA);
  const std::array<double, 7> pose = pose_;
  const std::array<double, 9> speed_bias = speed_bias_;
  const std::array<double, 3> b = features_.landmarks().at(kPointB).p_w;
  const PointReleaseResult r =
      ReleaseOrphanPoints(&features_, &prior_, &blocks_);
  EXPECT_EQ(r.released, 1);
  EXPECT_EQ(r.forgotten, 1);
  EXPECT_FALSE(r.failed);
  EXPECT_EQ(r.marginalization.status, MarginalizationStatus::kOk);

  EXPECT_EQ(features_.landmarks().count(kPointA), 0u);
  EXPECT_EQ(features_.landmarks().count(kPointB), 1u);
  EXPECT_EQ(features_.landmarks().count(kOrdinary), 1u);
  EXPECT_TRUE(features_.OrphanPoints().empty());

  ASSERT_TRUE(prior_);
  const std::vector<double*> kept = {pose_.data(), speed_bias_.data(),
                                     P(kPointB)};
  EXPECT_EQ(blocks_, kept);
  ASSERT_EQ(prior_->blocks().size(), 3u);
  EXPECT_EQ(prior_->parameter_block_sizes(), (std::vector<int32_t>{7, 9, 3}));
  EXPECT_EQ(prior_->jacobian().cols(), kDim - 3);
  EXPECT_EQ(prior_->information().rows(), kDim - 3);
  EXPECT_EQ(prior_->blocks()[2].x0, std::vector<double>(b.begin(), b.end()));
  // The release moves no state.
  EXPECT_EQ(pose_, pose);
  EXPECT_EQ(speed_bias_, speed_bias);
  EXPECT_EQ(features_.landmarks().at(kPointB).p_w, b);
}

TEST_F(PointRelease, LeavesTheSchurComplementOfThePoint) {
  // At x = x0 the prior's tangent Jacobian is J: H = J^T J, g = J^T r0.
  const Eigen::MatrixXd H = J_.transpose() * J_;
  const Eigen::VectorXd g = J_.transpose() * r0_;
  Orphan(kPointA);
  ASSERT_FALSE(ReleaseOrphanPoints(&features_, &prior_, &blocks_).failed);

  const Eigen::MatrixXd H_kk = Without(Without(H, kA).transpose(), kA);
  const Eigen::MatrixXd H_km = Without(H.middleCols(kA, 3), kA);
  const Eigen::Matrix3d H_mm = H.block<3, 3>(kA, kA);
  const Eigen::MatrixXd H_star =
      H_kk - H_km * H_mm.inverse() * H_km.transpose();
  const Eigen::VectorXd g_star =
      Without(g, kA) - H_km * H_mm.inverse() * g.segment<3>(kA);

  const Eigen::MatrixXd& info = prior_->information();
  ASSERT_EQ(info.rows(), kDim - 3);
  const double scale = H_star.norm();
  EXPECT_LT((info - H_star).norm(), 1e-10 * scale);
  EXPECT_LT((prior_->gradient0() - g_star).norm(), 1e-10 * scale);
  // The stored square root agrees with the information it claims.
  EXPECT_LT(
      (prior_->jacobian().transpose() * prior_->jacobian() - H_star).norm(),
      1e-10 * scale);
  // Finite, symmetric, positive semi-definite.
  EXPECT_TRUE(info.allFinite());
  EXPECT_TRUE(prior_->residual0().allFinite());
  EXPECT_LT((info - info.transpose()).norm(), 1e-12 * scale);
  const Eigen::VectorXd eig =
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(info).eigenvalues();
  EXPECT_GE(eig.minCoeff(), -1e-12 * eig.maxCoeff());
  EXPECT_GT(eig.minCoeff(), 0.0);  // J full rank: nothing lost on the rest
}

TEST_F(PointRelease, KeepsTheMinimiserAndTheCostOverTheOtherBlocks) {
  const std::unique_ptr<MarginalizationPrior> full = MakeFullPrior();
  const std::vector<double*> full_blocks = blocks_;
  const Eigen::VectorXd dx_full =
      -(J_.transpose() * J_).ldlt().solve(J_.transpose() * r0_);
  Orphan(kPointA);
  ASSERT_FALSE(ReleaseOrphanPoints(&features_, &prior_, &blocks_).failed);

  // The prior's minimiser on the kept blocks is the full one's.
  ASSERT_EQ(prior_->information().rows(), kDim - 3);
  const Eigen::VectorXd dx_kept =
      -prior_->information().ldlt().solve(prior_->gradient0());
  EXPECT_LT((dx_kept - Without(dx_full, kA)).norm(), 1e-10 * dx_full.norm());

  // Away from x0 too: the released prior's cost is the full prior's
  // minimised over the point (which enters it linearly: r = a + J_A dp),
  // up to one constant. Point A's block still lives here for the full prior.
  std::array<double, 3> point_a = {0.5, -0.2, 5.0};
  std::vector<double*> with_a = full_blocks;
  with_a[2] = point_a.data();
  const Eigen::MatrixXd J_A = J_.middleCols(kA, 3);
  std::mt19937 rng(7);
  std::normal_distribution<double> n(0.0, 0.05);
  double offset = std::numeric_limits<double>::quiet_NaN();
  for (int trial = 0; trial < 5; ++trial) {
    Eigen::Map<Eigen::Vector3d>(pose_.data()) +=
        Eigen::Vector3d(n(rng), n(rng), n(rng));
    Eigen::Map<Eigen::Quaterniond> q(pose_.data() + 3);
    q = (q * Eigen::Quaterniond(Eigen::AngleAxisd(
                 3 * n(rng), Eigen::Vector3d(n(rng), n(rng), 1).normalized())))
            .normalized();
    for (double& v : speed_bias_) v += n(rng);
    for (int i = 0; i < 3; ++i) P(kPointB)[i] += n(rng);

    Eigen::VectorXd a;
    Cost(*full, with_a, &a);
    const Eigen::Vector3d dp =
        -(J_A.transpose() * J_A).ldlt().solve(J_A.transpose() * a);
    const double min_full = 0.5 * (a + J_A * dp).squaredNorm();
    const double released = Cost(*prior_, blocks_);
    if (trial == 0) offset = released - min_full;
    EXPECT_NEAR(released - min_full, offset, 1e-9 * (1.0 + min_full))
        << "trial " << trial;
  }
}

TEST_F(PointRelease, TwoOrphansShrinkThePriorBySix) {
  Orphan(kPointA);
  Orphan(kPointB);
  const PointReleaseResult r =
      ReleaseOrphanPoints(&features_, &prior_, &blocks_);
  EXPECT_EQ(r.released, 2);
  EXPECT_EQ(r.forgotten, 2);
  EXPECT_EQ(features_.landmarks().size(), 1u);
  const std::vector<double*> kept = {pose_.data(), speed_bias_.data()};
  EXPECT_EQ(blocks_, kept);
  ASSERT_EQ(prior_->information().rows(), kDim - 6);
  const Eigen::MatrixXd H = J_.transpose() * J_;
  const Eigen::MatrixXd H_kk = H.topLeftCorner(kA, kA);
  const Eigen::MatrixXd H_km = H.topRightCorner(kA, 6);
  const Eigen::MatrixXd H_star =
      H_kk - H_km * H.bottomRightCorner(6, 6).inverse() * H_km.transpose();
  EXPECT_LT((prior_->information() - H_star).norm(), 1e-10 * H_star.norm());
}

TEST_F(PointRelease, AnOrphanThePriorDoesNotHoldIsOnlyForgotten) {
  blocks_.pop_back();  // a prior without point B
  std::vector<PriorBlock> b(prior_->blocks().begin(),
                            prior_->blocks().end() - 1);
  prior_ = std::make_unique<MarginalizationPrior>(b, J_.topLeftCorner(kB, kB),
                                                  r0_.head(kB));
  const MarginalizationPrior* before = prior_.get();
  Orphan(kPointB);
  const PointReleaseResult r =
      ReleaseOrphanPoints(&features_, &prior_, &blocks_);
  EXPECT_EQ(r.released, 0);
  EXPECT_EQ(r.forgotten, 1);
  EXPECT_EQ(prior_.get(), before);
  EXPECT_EQ(blocks_.size(), 3u);
  EXPECT_EQ(features_.landmarks().count(kPointB), 0u);
  EXPECT_EQ(features_.landmarks().count(kPointA), 1u);

  // Without a prior at all, the same.
  prior_.reset();
  blocks_.clear();
  Orphan(kPointA);
  EXPECT_EQ(ReleaseOrphanPoints(&features_, &prior_, &blocks_).forgotten, 1);
  EXPECT_FALSE(prior_);
}

TEST_F(PointRelease, NoOrphanChangesNothing) {
  const MarginalizationPrior* before = prior_.get();
  const PointReleaseResult r =
      ReleaseOrphanPoints(&features_, &prior_, &blocks_);
  EXPECT_EQ(r.released + r.forgotten, 0);
  EXPECT_EQ(prior_.get(), before);
  EXPECT_EQ(blocks_.size(), 4u);
  EXPECT_EQ(features_.landmarks().size(), 3u);
}

TEST_F(PointRelease, AFailedMarginalizationLeavesThePriorToTheCaller) {
  // A non-finite kept value: the prior cannot be evaluated, no information.
  speed_bias_[0] = std::numeric_limits<double>::quiet_NaN();
  const MarginalizationPrior* before = prior_.get();
  Orphan(kPointA);
  const PointReleaseResult r =
      ReleaseOrphanPoints(&features_, &prior_, &blocks_);
  EXPECT_TRUE(r.failed);
  EXPECT_EQ(r.released, 1);
  EXPECT_EQ(prior_.get(), before);
  EXPECT_EQ(blocks_.size(), 4u);
  EXPECT_EQ(features_.landmarks().count(kPointA), 0u);
}

}  // namespace
}  // namespace vio
