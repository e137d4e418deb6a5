// Marginalisation under bad input: broken residual blocks, rank-deficient
// marginal blocks, non-finite values, inconsistent problems. Each gives a
// status (and counters) and never a NaN.

#include <ceres/manifold.h>
#include <ceres/sized_cost_function.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "estimator/marginalization.h"
#include "test/testing/marginalization_window.h"
#include "test/testing/pose_test_factors.h"

namespace vio {
namespace {

using testing::MaxAbs;
using testing::PointTestFactor;
using testing::Residual;

// The shared window, for the tests of bad input.
class MarginalizationBadInputTest : public testing::MarginalizationWindowTest {
};

// Returns a NaN residual, or fails, as a broken factor might.
class BrokenTestFactor final : public ceres::SizedCostFunction<1, 3> {
 public:
  explicit BrokenTestFactor(bool fail) : fail_(fail) {}
  bool Evaluate(double const* const*, double* residuals,
                double** jacobians) const override {
    residuals[0] = std::numeric_limits<double>::quiet_NaN();
    if (jacobians != nullptr && jacobians[0] != nullptr) {
      for (int i = 0; i < 3; ++i) jacobians[0][i] = 1.0;
    }
    return !fail_;
  }

 private:
  bool fail_;
};

bool AllFinite(const MarginalizationResult& r) {
  return r.jacobian.allFinite() && r.residual0.allFinite() &&
         r.information.allFinite() && r.gradient.allFinite();
}

TEST_F(MarginalizationBadInputTest, BrokenResidualBlocksAreSkippedAndCounted) {
  const std::vector<double*> marg = {Pose(0), Speed(0), Point(0)};
  const MarginalizationResult clean = Marginalize(ProblemFor(marg));
  MarginalizationProblem problem = ProblemFor(marg);
  const BrokenTestFactor nan_factor(false), failing_factor(true);
  problem.residual_blocks.push_back({&nan_factor, nullptr, {Point(0)}});
  problem.residual_blocks.push_back({&failing_factor, nullptr, {Speed(0)}});
  const MarginalizationResult result = Marginalize(problem);
  EXPECT_EQ(result.status, MarginalizationStatus::kDegenerate);
  EXPECT_EQ(result.num_skipped_residual_blocks, 2);
  EXPECT_EQ(result.num_residual_blocks_used, clean.num_residual_blocks_used);
  ASSERT_TRUE(AllFinite(result));
  EXPECT_LT(MaxAbs(result.information - clean.information),
            1e-12 * MaxAbs(clean.information));
}

// A point seen along one direction only (a rank-one observation) leaves
// H_mm rank deficient; it then carries no information to the pose, so the
// prior is exactly the pose factors' own information.
TEST_F(MarginalizationBadInputTest,
       RankDeficientMarginalBlockGivesStatusAndNoNaN) {
  Eigen::Matrix<double, 1, 3> e_x(10.0, 0.0, 0.0);
  const PointTestFactor one_direction(Eigen::Vector3d(1.0, 2.0, 3.0), e_x);
  const Residual& pose_prior = residuals_[0];  // touches pose 0 only
  const Residual& relative01 = residuals_[1];  // pose 0 - pose 1
  MarginalizationProblem problem;
  problem.parameter_blocks = AllBlocks();
  problem.residual_blocks = {
      {&one_direction, nullptr, {Pose(0), Point(0)}},
      {pose_prior.cost.get(), nullptr, pose_prior.blocks},
      {relative01.cost.get(), nullptr, relative01.blocks}};
  // Speed 0 is listed for marginalisation but no residual touches it.
  problem.marginalized = {Point(0), Speed(0)};
  const MarginalizationResult result = Marginalize(problem);
  EXPECT_EQ(result.status, MarginalizationStatus::kDegenerate);
  EXPECT_EQ(result.marginalized_rank_deficiency, 2 + 3);
  ASSERT_TRUE(AllFinite(result));

  Eigen::MatrixXd H;
  Eigen::VectorXd g;
  CeresLinearise({&pose_prior, &relative01}, result.kept_parameter_blocks, &H,
                 &g);
  EXPECT_LT(MaxAbs(result.information - H), 1e-9 * MaxAbs(H));
  EXPECT_LT((result.gradient - g).cwiseAbs().maxCoeff(),
            1e-9 * g.cwiseAbs().maxCoeff());
}

TEST_F(MarginalizationBadInputTest, NonFiniteParameterFailsWithMessage) {
  const std::vector<double*> marg = {Pose(0), Speed(0), Point(0)};
  Speed(1)[2] = std::numeric_limits<double>::quiet_NaN();
  const MarginalizationResult result = Marginalize(ProblemFor(marg));
  EXPECT_EQ(result.status, MarginalizationStatus::kFailed);
  EXPECT_NE(result.message.find("non-finite"), std::string::npos)
      << result.message;
  EXPECT_EQ(result.jacobian.size(), 0);
}

TEST_F(MarginalizationBadInputTest, NoUsableResidualFails) {
  const BrokenTestFactor nan_factor(false);
  MarginalizationProblem problem;
  problem.parameter_blocks = AllBlocks();
  problem.residual_blocks = {{&nan_factor, nullptr, {Point(0)}},
                             {&nan_factor, nullptr, {Point(1)}}};
  problem.marginalized = {Point(0)};
  const MarginalizationResult result = Marginalize(problem);
  EXPECT_EQ(result.status, MarginalizationStatus::kFailed);
  EXPECT_EQ(result.num_skipped_residual_blocks, 2);
}

TEST_F(MarginalizationBadInputTest, ResidualOnUnlistedBlockFails) {
  MarginalizationProblem problem = ProblemFor({Pose(0)});
  double unlisted[3] = {0.0, 0.0, 0.0};
  const BrokenTestFactor factor(false);
  problem.residual_blocks.push_back({&factor, nullptr, {unlisted}});
  const MarginalizationResult result = Marginalize(problem);
  EXPECT_EQ(result.status, MarginalizationStatus::kFailed);
  EXPECT_NE(result.message.find("unlisted"), std::string::npos);
}

TEST_F(MarginalizationBadInputTest, KeptBlockWithForeignManifoldFails) {
  MarginalizationProblem problem = ProblemFor({Pose(0)});
  const ceres::SubsetManifold fix_x(3, {0});
  for (auto& p : problem.parameter_blocks) {
    if (p.values == Speed(0)) p.manifold = &fix_x;
  }
  const MarginalizationResult result = Marginalize(problem);
  EXPECT_EQ(result.status, MarginalizationStatus::kFailed);
  EXPECT_NE(result.message.find("parameter block 4 is kept"), std::string::npos)
      << result.message;
}

}  // namespace
}  // namespace vio
