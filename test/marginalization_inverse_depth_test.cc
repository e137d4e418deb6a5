// Marginalisation with inverse depths leaving (the estimator's case): the
// scalars' closed-form elimination, the Cholesky square root and its
// eigen-decomposition fallback, against a dense Schur complement of Ceres'
// own linearisation.

#include <ceres/sized_cost_function.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <vector>

#include "estimator/marginalization.h"
#include "test/testing/inverse_depth_window.h"

namespace vio {
namespace {

using testing::InverseDepthWindow;
using Residual = InverseDepthWindow::Residual;

double MaxAbs(const Eigen::MatrixXd& m) { return m.cwiseAbs().maxCoeff(); }

// r = 0 * x: a residual that carries no information on its scalar.
class NoInformationTestFactor final : public ceres::SizedCostFunction<1, 1> {
 public:
  bool Evaluate(double const* const*, double* r, double** J) const override {
    r[0] = 0.0;
    if (J != nullptr && J[0] != nullptr) J[0][0] = 0.0;
    return true;
  }
};

class MarginalizationInverseDepthTest : public ::testing::Test {
 protected:
  // Huber only: the marginalisation's first-order loss handling is then
  // exactly Ceres' corrector (rho'' <= 0).
  MarginalizationInverseDepthTest() : w_(/*tolerant_loss=*/false) {}

  // Pose 0 and the depths anchored in it leave.
  std::vector<double*> Leaving() {
    std::vector<double*> m = {w_.Pose(0)};
    for (int k = 0; k < InverseDepthWindow::kLandmarks; ++k) {
      if (w_.AnchorOf(k) == 0) m.push_back(w_.Rho(k));
    }
    return m;
  }

  std::vector<const Residual*> Touching(const std::vector<double*>& m,
                                        bool with_prior) {
    std::vector<const Residual*> out;
    for (const Residual& r : w_.residuals()) {
      if (r.anchor < 0 && !with_prior) continue;
      bool touches = false;
      for (double* b : r.blocks) {
        for (double* x : m) touches = touches || b == x;
      }
      if (touches) out.push_back(&r);
    }
    return out;
  }

  MarginalizationProblem ProblemFor(const std::vector<double*>& m,
                                    const std::vector<const Residual*>& rs) {
    MarginalizationProblem p;
    for (int i = 0; i < InverseDepthWindow::kPoses; ++i) {
      p.parameter_blocks.push_back({w_.Pose(i), 7, w_.pose_manifold(), false});
    }
    p.parameter_blocks.push_back(
        {w_.Extrinsic(), 7, w_.pose_manifold(), /*constant=*/true});
    for (int k = 0; k < InverseDepthWindow::kLandmarks; ++k) {
      p.parameter_blocks.push_back({w_.Rho(k), 1, nullptr, false});
    }
    for (const Residual* r : rs) {
      p.residual_blocks.push_back({r->cost.get(), r->loss, r->blocks});
    }
    p.marginalized.assign(m.begin(), m.end());
    return p;
  }

  // H* and g* of the residuals by Ceres' linearisation and a full inverse.
  void DenseSchur(const std::vector<double*>& m,
                  const std::vector<double*>& kept,
                  const std::vector<const Residual*>& rs,
                  Eigen::MatrixXd* H_star, Eigen::VectorXd* g_star) {
    std::vector<double*> order = m;
    order.insert(order.end(), kept.begin(), kept.end());
    Eigen::MatrixXd H;
    Eigen::VectorXd g;
    w_.CeresLinearise(rs, order, &H, &g);
    int ms = 0;
    for (double* b : m) ms += w_.TangentSize(b);
    const int ks = static_cast<int>(H.rows()) - ms;
    const Eigen::MatrixXd inv = H.topLeftCorner(ms, ms).inverse();
    *H_star = H.bottomRightCorner(ks, ks) -
              H.bottomLeftCorner(ks, ms) * inv * H.topRightCorner(ms, ks);
    *g_star = g.tail(ks) - H.bottomLeftCorner(ks, ms) * inv * g.head(ms);
  }

  InverseDepthWindow w_;
};

TEST_F(MarginalizationInverseDepthTest, ScalarEliminationEqualsDenseSchur) {
  const std::vector<double*> m = Leaving();
  ASSERT_GT(m.size(), 10u);
  const std::vector<const Residual*> rs = Touching(m, /*with_prior=*/true);
  const MarginalizationResult result = Marginalize(ProblemFor(m, rs));
  ASSERT_EQ(result.status, MarginalizationStatus::kOk) << result.message;
  // The prior holds the gauge: H* is positive definite, the Cholesky path.
  EXPECT_EQ(result.num_floored_eigenvalues, 0);
  EXPECT_TRUE(result.jacobian.isUpperTriangular());

  Eigen::MatrixXd H_star;
  Eigen::VectorXd g_star;
  DenseSchur(m, result.kept_parameter_blocks, rs, &H_star, &g_star);
  const double h = MaxAbs(H_star), g = g_star.cwiseAbs().maxCoeff();
  EXPECT_LT(MaxAbs(result.information - H_star), 1e-9 * h);
  EXPECT_LT((result.gradient - g_star).cwiseAbs().maxCoeff(), 1e-9 * g);
  const Eigen::MatrixXd& J = result.jacobian;
  EXPECT_LT(MaxAbs(J.transpose() * J - H_star), 1e-9 * h);
  EXPECT_LT((J.transpose() * result.residual0 - g_star).cwiseAbs().maxCoeff(),
            1e-9 * g);
  // The prior made from it carries the same J^T J.
  EXPECT_LT(MaxAbs(result.MakePrior()->information() - H_star), 1e-9 * h);
}

TEST_F(MarginalizationInverseDepthTest,
       DepthWithoutInformationIsDroppedAndCounted) {
  const std::vector<double*> m = Leaving();
  const std::vector<const Residual*> rs = Touching(m, true);
  const MarginalizationResult clean = Marginalize(ProblemFor(m, rs));
  // A further depth leaves that no residual informs.
  double lonely = 0.2;
  const NoInformationTestFactor nothing;
  MarginalizationProblem p = ProblemFor(m, rs);
  p.parameter_blocks.push_back({&lonely, 1, nullptr, false});
  p.residual_blocks.push_back({&nothing, nullptr, {&lonely}});
  p.marginalized.push_back(&lonely);
  const MarginalizationResult result = Marginalize(p);
  EXPECT_EQ(result.status, MarginalizationStatus::kDegenerate);
  EXPECT_EQ(result.marginalized_rank_deficiency, 1);
  EXPECT_LT(MaxAbs(result.information - clean.information),
            1e-12 * MaxAbs(clean.information));
}

TEST_F(MarginalizationInverseDepthTest, SingularSchurTakesTheEigenPath) {
  // Without the prior the kept poses hold only relative information: the
  // gauge (6) and the scale (1) of a visual-only window are free.
  const std::vector<double*> m = Leaving();
  const std::vector<const Residual*> rs = Touching(m, /*with_prior=*/false);
  const MarginalizationResult result = Marginalize(ProblemFor(m, rs));
  ASSERT_TRUE(result.ok()) << result.message;
  EXPECT_GE(result.num_floored_eigenvalues, 7);
  EXPECT_TRUE(result.jacobian.allFinite() && result.residual0.allFinite());
  Eigen::MatrixXd H_star;
  Eigen::VectorXd g_star;
  DenseSchur(m, result.kept_parameter_blocks, rs, &H_star, &g_star);
  const double h = MaxAbs(H_star);
  EXPECT_LT(MaxAbs(result.information - H_star), 1e-9 * h);
  // J^T J is H* with its null space raised to the floor (1e-10 of the max).
  EXPECT_LT(MaxAbs(result.jacobian.transpose() * result.jacobian - H_star),
            1e-8 * h);
}

}  // namespace
}  // namespace vio
