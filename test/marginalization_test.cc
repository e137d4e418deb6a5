#include "estimator/marginalization.h"

#include <ceres/problem.h>
#include <ceres/solver.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "factors/check/jacobian_check.h"
#include "factors/pose_manifold.h"
#include "test/testing/marginalization_window.h"
#include "test/testing/pose_test_factors.h"

namespace vio {
namespace {

using testing::Borrowed;
using testing::MarginalizationWindowTest;

using testing::DifferenceTestFactor;
using testing::MaxAbs;
using testing::Residual;

TEST_F(MarginalizationWindowTest, TestFactorJacobiansMatchNumericDiff) {
  for (const Residual& r : residuals_) {
    FactorInstance f;
    f.cost = std::make_unique<Borrowed>(r.cost.get());
    for (double* b : r.blocks) {
      f.blocks.emplace_back(b, b + SizeOf(b));
      f.manifolds.push_back(IsPose(b) ? std::make_shared<PoseManifold>()
                                      : nullptr);
    }
    std::vector<BlockJacobianError> errors;
    ASSERT_TRUE(CompareJacobians(f, {}, &errors));
    for (const auto& e : errors) EXPECT_LT(e.max_rel_error, 1e-6) << e.block;
  }
}

// The prior's information J^T J and gradient J^T r0 equal the Schur
// complement of the linearised problem, which Ceres linearises here (with the
// Huber loss applied by Ceres' own corrector) and the test reduces densely
// with a full inverse.
TEST_F(MarginalizationWindowTest, PriorEqualsDenseSchurComplement) {
  const std::vector<double*> marg = {Pose(0), Speed(0), Point(0)};
  const MarginalizationResult result = Marginalize(ProblemFor(marg));
  ASSERT_EQ(result.status, MarginalizationStatus::kOk) << result.message;
  // These residual blocks alone hold only relative information on the kept
  // blocks (the gauge is in the pose-0 prior, which leaves): H* has 6 zero
  // eigenvalues, which the floor raises to 1e-10 of the largest.
  EXPECT_EQ(result.num_floored_eigenvalues, 6);

  Eigen::MatrixXd H_star;
  Eigen::VectorXd g_star;
  DenseSchur(marg, result.kept_parameter_blocks, &H_star, &g_star);

  const double h_scale = MaxAbs(H_star), g_scale = g_star.cwiseAbs().maxCoeff();
  EXPECT_LT(MaxAbs(result.information - H_star), 1e-10 * h_scale);
  EXPECT_LT(MaxAbs(result.gradient - g_star), 1e-10 * g_scale);
  const Eigen::MatrixXd& J = result.jacobian;
  EXPECT_LT(MaxAbs(J.transpose() * J - H_star), 1e-9 * h_scale);
  EXPECT_LT(MaxAbs(J.transpose() * result.residual0 - g_star), 1e-10 * g_scale);

  // The Huber loss is exercised: some point residuals lie beyond c = 1.
  int robust = 0;
  for (const Residual* r : Select(marg, true)) {
    if (r->loss == nullptr) continue;
    std::vector<const double*> p(r->blocks.begin(), r->blocks.end());
    Eigen::VectorXd res(r->cost->num_residuals());
    ASSERT_TRUE(r->cost->Evaluate(p.data(), res.data(), nullptr));
    robust += res.squaredNorm() > 1.0 ? 1 : 0;
  }
  EXPECT_GT(robust, 0);

  // The prior itself, linearised by Ceres at x = x0, carries the same.
  const std::unique_ptr<MarginalizationPrior> prior = result.MakePrior();
  Residual prior_residual{std::shared_ptr<ceres::CostFunction>(
                              prior.get(), [](ceres::CostFunction*) {}),
                          nullptr, result.kept_parameter_blocks};
  Eigen::MatrixXd H_prior;
  Eigen::VectorXd g_prior;
  CeresLinearise({&prior_residual}, result.kept_parameter_blocks, &H_prior,
                 &g_prior);
  EXPECT_LT(MaxAbs(H_prior - H_star), 1e-9 * h_scale);
  EXPECT_LT(MaxAbs(g_prior - g_star), 1e-10 * g_scale);
}

// One Gauss-Newton step of the whole problem, restricted to the kept blocks,
// equals the step of the reduced problem: the prior plus the residual blocks
// that did not touch the marginalised blocks.
TEST_F(MarginalizationWindowTest, GaussNewtonStepWithPriorEqualsFullStep) {
  const std::vector<double*> marg = {Pose(0), Speed(0), Point(0)};
  const MarginalizationResult result = Marginalize(ProblemFor(marg));
  ASSERT_TRUE(result.ok()) << result.message;

  std::vector<double*> rest_order = result.kept_parameter_blocks;
  for (const auto& block : AllBlocks()) {
    bool listed = false;
    for (double* b : rest_order) listed = listed || b == block.values;
    for (double* b : marg) listed = listed || b == block.values;
    if (!listed) rest_order.push_back(block.values);
  }
  std::vector<double*> full_order = marg;
  full_order.insert(full_order.end(), rest_order.begin(), rest_order.end());

  Eigen::MatrixXd H_full;
  Eigen::VectorXd g_full;
  std::vector<const Residual*> all;
  for (const Residual& r : residuals_) all.push_back(&r);
  CeresLinearise(all, full_order, &H_full, &g_full);
  const Eigen::VectorXd dx_full = H_full.ldlt().solve(-g_full);

  const std::unique_ptr<MarginalizationPrior> prior = result.MakePrior();
  std::vector<const Residual*> reduced = Select(marg, false);
  Residual prior_residual{std::shared_ptr<ceres::CostFunction>(
                              prior.get(), [](ceres::CostFunction*) {}),
                          nullptr, result.kept_parameter_blocks};
  reduced.push_back(&prior_residual);
  Eigen::MatrixXd H_reduced;
  Eigen::VectorXd g_reduced;
  CeresLinearise(reduced, rest_order, &H_reduced, &g_reduced);
  const Eigen::VectorXd dx_reduced = H_reduced.ldlt().solve(-g_reduced);

  const int m = TangentSizeOf(marg, *this);
  const Eigen::VectorXd dx_kept = dx_full.tail(dx_full.size() - m);
  ASSERT_EQ(dx_kept.size(), dx_reduced.size());
  EXPECT_GT(dx_kept.norm(), 1e-3);  // the step is not trivially zero
  // Both sides are dense LDLT solves of a stiff system (weights from 10 to
  // 100, Huber-scaled rows); measured: 2.8e-9 relative.
  EXPECT_LT((dx_kept - dx_reduced).cwiseAbs().maxCoeff(),
            1e-8 * dx_kept.cwiseAbs().maxCoeff());
}

// Marginalising pose 0 and then pose 1 (re-marginalising the first prior)
// leaves the same information as marginalising both at once.
TEST_F(MarginalizationWindowTest, RemarginalisingAPriorEqualsOneStep) {
  const std::vector<double*> first = {Pose(0), Speed(0), Point(0)};
  const MarginalizationResult step1 = Marginalize(ProblemFor(first));
  ASSERT_TRUE(step1.ok()) << step1.message;
  const std::unique_ptr<MarginalizationPrior> prior1 = step1.MakePrior();

  // Step 2 lists the first prior's kept blocks (as the estimator would) and
  // the window blocks the prior does not cover; the blocks of step 1 are gone.
  const std::vector<double*> second = {Pose(1), Speed(1)};
  const std::vector<double*> gone = first;
  MarginalizationProblem problem2;
  problem2.parameter_blocks = KeptParameterBlocks(step1, &pose_manifold_);
  for (const auto& p : AllBlocks()) {
    bool listed = false;
    for (const auto& q : problem2.parameter_blocks) {
      listed = listed || q.values == p.values;
    }
    for (double* g : gone) listed = listed || g == p.values;
    if (!listed) problem2.parameter_blocks.push_back(p);
  }
  for (const Residual& r : residuals_) {
    if (Touches(r, second) && !Touches(r, gone)) {
      problem2.residual_blocks.push_back(
          {r.cost.get(), r.loss.get(), r.blocks});
    }
  }
  problem2.residual_blocks.push_back(PriorResidualBlock(step1, prior1.get()));
  problem2.marginalized.assign(second.begin(), second.end());
  const MarginalizationResult step2 = Marginalize(problem2);
  ASSERT_TRUE(step2.ok()) << step2.message;

  std::vector<double*> both = first;
  both.insert(both.end(), second.begin(), second.end());
  const MarginalizationResult once = Marginalize(ProblemFor(both));
  ASSERT_TRUE(once.ok()) << once.message;

  // Compare block by block (the two results may order the kept blocks
  // differently).
  auto offsets = [this](const MarginalizationResult& r) {
    std::map<const double*, int> o;
    int offset = 0;
    for (double* b : r.kept_parameter_blocks) {
      o[b] = offset;
      offset += IsPose(b) ? 6 : 3;
    }
    return o;
  };
  const auto o2 = offsets(step2), o1 = offsets(once);
  ASSERT_EQ(o2.size(), o1.size());
  const double scale = MaxAbs(once.information);
  for (const auto& [a, ia] : o1) {
    ASSERT_EQ(o2.count(a), 1u);
    EXPECT_LT((step2.gradient.segment(o2.at(a), SizeOf(a) == 7 ? 6 : 3) -
               once.gradient.segment(ia, SizeOf(a) == 7 ? 6 : 3))
                  .cwiseAbs()
                  .maxCoeff(),
              1e-9 * once.gradient.cwiseAbs().maxCoeff());
    for (const auto& [b, ib] : o1) {
      const int na = IsPose(a) ? 6 : 3, nb = IsPose(b) ? 6 : 3;
      EXPECT_LT(MaxAbs(step2.information.block(o2.at(a), o2.at(b), na, nb) -
                       once.information.block(ia, ib, na, nb)),
                1e-9 * scale);
    }
  }
}

// A block held constant (say, a fixed extrinsic) gets no columns and is not
// kept: the result is the Schur complement with that block fixed.
TEST_F(MarginalizationWindowTest, ConstantBlockIsNeitherColumnNorKept) {
  const std::vector<double*> marg = {Pose(0), Speed(0), Point(0)};
  MarginalizationProblem problem = ProblemFor(marg);
  for (auto& p : problem.parameter_blocks) {
    if (p.values == Point(1)) p.constant = true;
  }
  const MarginalizationResult result = Marginalize(problem);
  ASSERT_TRUE(result.ok()) << result.message;
  for (double* b : result.kept_parameter_blocks) EXPECT_NE(b, Point(1));
  Eigen::MatrixXd H_star;
  Eigen::VectorXd g_star;
  // Ceres holds the blocks missing from the evaluation order constant.
  DenseSchur(marg, result.kept_parameter_blocks, &H_star, &g_star);
  EXPECT_LT(MaxAbs(result.information - H_star), 1e-10 * MaxAbs(H_star));
  EXPECT_LT((result.gradient - g_star).cwiseAbs().maxCoeff(),
            1e-10 * g_star.cwiseAbs().maxCoeff());
}

// On a linear problem the prior is exact: Ceres solving the window with the
// prior in place of the leaving block reaches the full problem's solution on
// the kept blocks.
TEST(Marginalization, CeresSolveWithPriorMatchesFullSolveOnLinearChain) {
  constexpr int kBlocks = 5;
  std::mt19937 rng(3);
  std::normal_distribution<double> n(0.0, 1.0);
  std::vector<std::vector<double>> x(kBlocks, std::vector<double>(3, 0.0));
  std::vector<double> origin = {0.0, 0.0, 0.0};
  std::vector<std::unique_ptr<DifferenceTestFactor>> factors;
  std::vector<std::vector<double*>> blocks;
  for (int i = 0; i < kBlocks; ++i) {
    Eigen::Matrix3d W = Eigen::Matrix3d::Identity() * (5.0 + i);
    W(0, 1) = 1.0;
    double* from = i == 0 ? origin.data() : x[i - 1].data();
    factors.push_back(std::make_unique<DifferenceTestFactor>(
        Eigen::Vector3d(1.0 + n(rng), n(rng), n(rng)), W));
    blocks.push_back({from, x[i].data()});
  }
  // A second chain edge 0 -> 2 so that block 0 couples two kept blocks.
  factors.push_back(std::make_unique<DifferenceTestFactor>(
      Eigen::Vector3d(2.0, 0.5, -0.5), 3.0 * Eigen::Matrix3d::Identity()));
  blocks.push_back({x[0].data(), x[2].data()});

  MarginalizationProblem problem;
  problem.parameter_blocks.push_back({origin.data(), 3, nullptr, true});
  for (auto& b : x) problem.parameter_blocks.push_back({b.data(), 3});
  for (size_t f = 0; f < factors.size(); ++f) {
    const bool touches_0 =
        blocks[f][0] == x[0].data() || blocks[f][1] == x[0].data();
    if (touches_0)
      problem.residual_blocks.push_back({factors[f].get(), nullptr, blocks[f]});
  }
  problem.marginalized = {x[0].data()};
  const MarginalizationResult result = Marginalize(problem);
  ASSERT_EQ(result.status, MarginalizationStatus::kOk) << result.message;

  auto solve = [&](bool with_prior) {
    std::vector<std::vector<double>> saved = x;
    ceres::Problem::Options options;
    options.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    ceres::Problem ceres_problem(options);
    for (size_t f = 0; f < factors.size(); ++f) {
      const bool touches_0 =
          blocks[f][0] == x[0].data() || blocks[f][1] == x[0].data();
      if (!with_prior || !touches_0) {
        ceres_problem.AddResidualBlock(factors[f].get(), nullptr, blocks[f]);
      }
    }
    std::unique_ptr<MarginalizationPrior> prior = result.MakePrior();
    if (with_prior) {
      ceres_problem.AddResidualBlock(prior.get(), nullptr,
                                     result.kept_parameter_blocks);
    }
    if (ceres_problem.HasParameterBlock(origin.data())) {
      ceres_problem.SetParameterBlockConstant(origin.data());
    }
    ceres::Solver::Options solver;
    solver.max_num_iterations = 10;
    // A huge trust region makes LM's first step the Gauss-Newton step, which
    // solves a linear problem exactly.
    solver.initial_trust_region_radius = 1e16;
    solver.function_tolerance = 1e-16;
    solver.gradient_tolerance = 1e-16;
    solver.parameter_tolerance = 1e-16;
    ceres::Solver::Summary summary;
    ceres::Solve(solver, &ceres_problem, &summary);
    std::vector<std::vector<double>> solution = x;
    x = saved;
    return solution;
  };
  const auto full = solve(false);
  const auto reduced = solve(true);
  for (int i = 1; i < kBlocks; ++i) {
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(full[i][k], reduced[i][k], 1e-11) << "block " << i;
    }
  }
  EXPECT_GT(std::abs(full[kBlocks - 1][0]), 1.0);  // the solve moved x
}

}  // namespace
}  // namespace vio
