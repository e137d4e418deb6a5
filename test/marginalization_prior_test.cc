#include "factors/marginalization_prior.h"

#include <ceres/gradient_checker.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

#include "factors/check/factor_cases.h"
#include "factors/check/jacobian_check.h"
#include "factors/pose_manifold.h"
#include "geometry/so3.h"

namespace vio {
namespace {

FactorCase PriorCase() {
  for (const FactorCase& c : AllFactorCases()) {
    if (c.name == "marginalization_prior") return c;
  }
  ADD_FAILURE() << "marginalization_prior is not registered";
  return MakeMarginalizationPriorCase();
}

std::vector<const double*> Pointers(const FactorInstance& f) {
  std::vector<const double*> p;
  for (const auto& b : f.blocks) p.push_back(b.data());
  return p;
}

TEST(MarginalizationPrior, IsRegisteredAsAFactorCase) {
  bool found = false;
  for (const FactorCase& c : AllFactorCases()) {
    found = found || c.name == "marginalization_prior";
  }
  EXPECT_TRUE(found);
}

TEST(MarginalizationPrior, JacobianMatchesNumericDiffAt200States) {
  const FactorCase c = PriorCase();
  std::mt19937 rng(7);
  JacobianCheckOptions options;
  for (int trial = 0; trial < 200; ++trial) {
    const FactorInstance f = c.sample(rng);
    std::vector<BlockJacobianError> errors;
    ASSERT_TRUE(CompareJacobians(f, options, &errors)) << "trial " << trial;
    for (const auto& e : errors) {
      EXPECT_LE(e.max_rel_error, c.tolerance)
          << "trial " << trial << " block " << e.block;
    }
  }
}

TEST(MarginalizationPrior, GradientCheckerAgrees) {
  const FactorCase c = PriorCase();
  std::mt19937 rng(8);
  // The checker differentiates in the ambient space with Ridders'
  // extrapolation. Its default first step (1e-2 of the value, 5e-3 on a
  // quaternion coefficient of 0.5) ended 3e-5 (relative) away from central
  // differences at any small step; a first step of 1e-4 agrees to 1e-11.
  ceres::NumericDiffOptions numeric;
  numeric.ridders_relative_initial_step_size = 1e-4;
  for (int trial = 0; trial < 20; ++trial) {
    const FactorInstance f = c.sample(rng);
    std::vector<const ceres::Manifold*> manifolds;
    for (const auto& m : f.manifolds) manifolds.push_back(m.get());
    ceres::GradientChecker checker(f.cost.get(), &manifolds, numeric);
    ceres::GradientChecker::ProbeResults results;
    // Its error is per entry (not per block): near-zero entries (1e-7 next to
    // 1e2) carry 1e-12 absolute errors, 1e-5 relative.
    EXPECT_TRUE(checker.Probe(Pointers(f).data(), 1e-4, &results))
        << "trial " << trial << ": " << results.error_log;
  }
}

// At x = x0 the residual is r0 and the tangent Jacobian is J itself.
TEST(MarginalizationPrior, AtLinearisationPointGivesR0AndJ) {
  std::mt19937 rng(9);
  FactorInstance f = PriorCase().sample(rng);
  const auto* prior = static_cast<const MarginalizationPrior*>(f.cost.get());
  std::vector<const double*> x0;
  for (const PriorBlock& b : prior->blocks()) x0.push_back(b.x0.data());
  Eigen::VectorXd r(prior->num_residuals());
  ASSERT_TRUE(prior->Evaluate(x0.data(), r.data(), nullptr));
  EXPECT_TRUE(r.isApprox(prior->residual0(), 1e-14));

  // Pose 0's tangent Jacobian = ambient Jacobian * PlusJacobian at x0.
  using RowMajor =
      Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  std::vector<RowMajor> ambient;
  std::vector<double*> jacobians;
  for (const PriorBlock& b : prior->blocks()) {
    ambient.emplace_back(prior->num_residuals(), b.AmbientSize());
  }
  for (auto& a : ambient) jacobians.push_back(a.data());
  ASSERT_TRUE(prior->Evaluate(x0.data(), r.data(), jacobians.data()));
  const Eigen::MatrixXd tangent =
      ambient[0] * PoseManifold::PlusJacobianAt(x0[0]);
  EXPECT_LT((tangent - prior->jacobian().leftCols<6>()).cwiseAbs().maxCoeff(),
            1e-9 * prior->jacobian().cwiseAbs().maxCoeff());
}

TEST(MarginalizationPrior, NonFiniteParameterFailsWithoutThrowing) {
  std::mt19937 rng(10);
  FactorInstance f = PriorCase().sample(rng);
  f.blocks[2][0] = std::numeric_limits<double>::quiet_NaN();
  Eigen::VectorXd r(f.cost->num_residuals());
  EXPECT_FALSE(f.cost->Evaluate(Pointers(f).data(), r.data(), nullptr));
}

TEST(MarginalizationPrior, RejectsInconsistentSizes) {
  const std::vector<PriorBlock> blocks = {
      {PriorBlockKind::kPose, {0, 0, 0, 0, 0, 0, 1}},
      {PriorBlockKind::kEuclidean, {1.0, 2.0}}};
  const Eigen::MatrixXd J = Eigen::MatrixXd::Identity(8, 8);
  EXPECT_NO_THROW(MarginalizationPrior(blocks, J, Eigen::VectorXd::Zero(8)));
  try {
    MarginalizationPrior(blocks, Eigen::MatrixXd::Identity(9, 9),
                         Eigen::VectorXd::Zero(9));
    FAIL() << "9 columns for 8 tangent coordinates accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("expected n x 8"), std::string::npos)
        << e.what();
  }
  const std::vector<PriorBlock> short_pose = {
      {PriorBlockKind::kPose, {0, 0, 0, 1}}};
  EXPECT_THROW(MarginalizationPrior(short_pose, Eigen::MatrixXd::Identity(6, 6),
                                    Eigen::VectorXd::Zero(6)),
               std::invalid_argument);
  Eigen::VectorXd r0 = Eigen::VectorXd::Zero(8);
  r0[3] = std::numeric_limits<double>::infinity();
  EXPECT_THROW(MarginalizationPrior(blocks, J, r0), std::invalid_argument);
}

// What a solver forming the normal equations itself relies on: J^T J and
// J^T r0 (computed, or the caller's J^T J checked for shape and finiteness),
// and M^T (J^T J) M, M^T (J^T r0 + J^T J dx) equal to the Gauss-Newton terms
// of the tangent Jacobian the prior's Evaluate returns.
TEST(MarginalizationPrior, NormalEquationTermsMatchItsJacobian) {
  std::mt19937 rng(12);
  const FactorInstance f = PriorCase().sample(rng);
  const auto& prior = static_cast<const MarginalizationPrior&>(*f.cost);
  const Eigen::MatrixXd& J = prior.jacobian();
  const double scale = (J.transpose() * J).cwiseAbs().maxCoeff();
  EXPECT_LT((prior.information() - J.transpose() * J).cwiseAbs().maxCoeff(),
            1e-12 * scale);
  EXPECT_LT((prior.gradient0() - J.transpose() * prior.residual0())
                .cwiseAbs()
                .maxCoeff(),
            1e-12 * scale);
  // The tangent Jacobian at the instance's (perturbed) values.
  const int m = prior.num_residuals();
  const int n = static_cast<int>(J.cols());
  Eigen::MatrixXd J_tan(m, n);
  std::vector<const double*> params = Pointers(f);
  std::vector<
      Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>
      ambient(f.blocks.size());
  std::vector<double*> ptrs;
  for (size_t b = 0; b < f.blocks.size(); ++b) {
    ambient[b].resize(m, static_cast<int>(f.blocks[b].size()));
    ptrs.push_back(ambient[b].data());
  }
  Eigen::VectorXd r(m);
  ASSERT_TRUE(prior.Evaluate(params.data(), r.data(), ptrs.data()));
  for (size_t b = 0; b < f.blocks.size(); ++b) {
    const int o = prior.TangentOffset(static_cast<int>(b));
    if (prior.blocks()[b].kind == PriorBlockKind::kPose) {
      J_tan.middleCols<6>(o) =
          ambient[b] * PoseManifold::PlusJacobianAt(f.blocks[b].data());
    } else {
      J_tan.middleCols(o, ambient[b].cols()) = ambient[b];
    }
  }
  Eigen::VectorXd dx;
  ASSERT_TRUE(prior.Delta(params.data(), &dx));
  Eigen::MatrixXd H = prior.information();
  Eigen::VectorXd g = prior.gradient0() + H * dx;
  for (size_t b = 0; b < f.blocks.size(); ++b) {
    if (prior.blocks()[b].kind != PriorBlockKind::kPose) continue;
    const int c = prior.TangentOffset(static_cast<int>(b)) + 3;
    const Eigen::Matrix3d M = RightJacobianInverse(dx.segment<3>(c));
    H.middleCols<3>(c) = H.middleCols<3>(c) * M;
    H.middleRows<3>(c) = M.transpose() * H.middleRows<3>(c);
    g.segment<3>(c) = M.transpose() * g.segment<3>(c);
  }
  EXPECT_LT((H - J_tan.transpose() * J_tan).cwiseAbs().maxCoeff(),
            1e-9 * scale);
  EXPECT_LT((g - J_tan.transpose() * r).cwiseAbs().maxCoeff(),
            1e-9 * std::max(1.0, g.cwiseAbs().maxCoeff()));

  EXPECT_THROW(MarginalizationPrior(prior.blocks(), J, prior.residual0(),
                                    Eigen::MatrixXd::Identity(n + 1, n + 1)),
               std::invalid_argument);
}

}  // namespace
}  // namespace vio
