#include "estimator/window_solver.h"

#include <ceres/problem.h>
#include <ceres/sized_cost_function.h>
#include <ceres/solver.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cstring>
#include <random>
#include <stdexcept>
#include <vector>

#include "test/testing/inverse_depth_window.h"

namespace vio {
namespace {

using testing::InverseDepthWindow;

// r = A p + c s - y: linear in a 3-vector p and a scalar s.
class LinearTestFactor final : public ceres::SizedCostFunction<2, 3, 1> {
 public:
  LinearTestFactor(const Eigen::Matrix<double, 2, 3>& A,
                   const Eigen::Vector2d& c, const Eigen::Vector2d& y)
      : A_(A), c_(c), y_(y) {}
  bool Evaluate(double const* const* p, double* r, double** J) const override {
    Eigen::Map<Eigen::Vector2d> residual(r);
    residual = A_ * Eigen::Map<const Eigen::Vector3d>(p[0]) + c_ * p[1][0] - y_;
    if (J != nullptr && J[0] != nullptr) {
      Eigen::Map<Eigen::Matrix<double, 2, 3, Eigen::RowMajor>> d_r_d_p(J[0]);
      d_r_d_p = A_;
    }
    if (J != nullptr && J[1] != nullptr) {
      Eigen::Map<Eigen::Vector2d> d_r_d_s(J[1]);
      d_r_d_s = c_;
    }
    return true;
  }

 private:
  Eigen::Matrix<double, 2, 3> A_;
  Eigen::Vector2d c_, y_;
};

// r = a - b on two scalars.
class PairTestFactor final : public ceres::SizedCostFunction<1, 1, 1> {
 public:
  bool Evaluate(double const* const* p, double* r, double** J) const override {
    r[0] = p[0][0] - p[1][0];
    if (J != nullptr && J[0] != nullptr) J[0][0] = 1.0;
    if (J != nullptr && J[1] != nullptr) J[1][0] = -1.0;
    return true;
  }
};

// r = x - target on a scalar.
class ScalarTestFactor final : public ceres::SizedCostFunction<1, 1> {
 public:
  ScalarTestFactor(double target, bool fail) : target_(target), fail_(fail) {}
  bool Evaluate(double const* const* p, double* r, double** J) const override {
    r[0] = p[0][0] - target_;
    if (J != nullptr && J[0] != nullptr) J[0][0] = 1.0;
    return !fail_;
  }

 private:
  double target_;
  bool fail_;
};

// The linear problem: 4 vectors (reduced) and 12 scalars (eliminated), each
// scalar seen with two of the vectors. Returns the stacked A and y of
// r = A x - y, x = [p_0..p_3, s_0..s_11].
struct LinearProblem {
  std::vector<Eigen::Vector3d> p = std::vector<Eigen::Vector3d>(4);
  std::vector<double> s = std::vector<double>(12);
  std::vector<std::unique_ptr<LinearTestFactor>> factors;
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(48, 24);
  Eigen::VectorXd y = Eigen::VectorXd::Zero(48);

  explicit LinearProblem(std::mt19937& rng) {
    std::normal_distribution<double> n(0.0, 1.0);
    for (auto& v : p) v = Eigen::Vector3d(n(rng), n(rng), n(rng));
    for (double& v : s) v = n(rng);
    int row = 0;
    for (int l = 0; l < 12; ++l) {
      for (int k : {l % 4, (l + 1) % 4}) {
        Eigen::Matrix<double, 2, 3> Ak;
        Eigen::Vector2d c(n(rng), n(rng)), yk(n(rng), n(rng));
        for (int i = 0; i < 6; ++i) Ak(i / 3, i % 3) = n(rng);
        factors.push_back(std::make_unique<LinearTestFactor>(Ak, c, yk));
        A.block<2, 3>(row, 3 * k) = Ak;
        A.block<2, 1>(row, 12 + l) = c;
        y.segment<2>(row) = yk;
        row += 2;
      }
    }
  }

  WindowSolverProblem Problem() {
    WindowSolverProblem problem;
    for (auto& v : p) problem.blocks.push_back({v.data(), 3});
    for (double& v : s) {
      WindowSolverBlock b{&v, 1};
      b.eliminated = true;
      problem.blocks.push_back(b);
    }
    for (int l = 0; l < 12; ++l) {
      int f = 2 * l;
      for (int k : {l % 4, (l + 1) % 4}) {
        WindowSolverResidual r;
        r.cost = factors[f++].get();
        r.first_block = static_cast<int>(problem.block_indices.size());
        r.num_blocks = 2;
        problem.block_indices.push_back(k);
        problem.block_indices.push_back(4 + l);
        problem.residuals.push_back(r);
      }
    }
    return problem;
  }
};

class WindowSolverLinearTest
    : public ::testing::TestWithParam<ceres::TrustRegionStrategyType> {};

// On a linear problem the solution is that of the normal equations, which
// Eigen's QR of the stacked system gives independently of the Schur route.
TEST_P(WindowSolverLinearTest, ReachesTheLeastSquaresSolution) {
  std::mt19937 rng(42);
  LinearProblem lp(rng);
  const Eigen::VectorXd expected = lp.A.colPivHouseholderQr().solve(lp.y);
  WindowSolverOptions options;
  options.trust_region = GetParam();
  options.max_iterations = 20;
  options.function_tolerance = 1e-14;
  const ceres::Solver::Summary summary = SolveWindow(lp.Problem(), options);
  EXPECT_NE(summary.termination_type, ceres::FAILURE) << summary.message;
  for (int k = 0; k < 4; ++k) {
    EXPECT_LT((lp.p[k] - expected.segment<3>(3 * k)).norm(), 1e-9) << k;
  }
  for (int l = 0; l < 12; ++l) {
    EXPECT_NEAR(lp.s[l], expected[12 + l], 1e-9) << l;
  }
  const double cost = 0.5 * (lp.A * expected - lp.y).squaredNorm();
  EXPECT_NEAR(summary.final_cost, cost, 1e-10 * cost);
}

INSTANTIATE_TEST_SUITE_P(Strategies, WindowSolverLinearTest,
                         ::testing::Values(ceres::DOGLEG,
                                           ceres::LEVENBERG_MARQUARDT));

WindowSolverProblem ProblemOf(InverseDepthWindow* w) {
  WindowSolverProblem problem;
  std::vector<double*> order;
  auto index_of = [&](double* b) {
    for (size_t i = 0; i < order.size(); ++i) {
      if (order[i] == b) return static_cast<int>(i);
    }
    order.push_back(b);
    WindowSolverBlock block;
    block.values = b;
    block.size = w->IsPose(b) ? 7 : 1;
    block.manifold = w->IsPose(b) ? w->pose_manifold() : nullptr;
    block.constant = b == w->Extrinsic();
    block.eliminated = !w->IsPose(b);
    problem.blocks.push_back(block);
    return static_cast<int>(order.size() - 1);
  };
  for (const InverseDepthWindow::Residual& r : w->residuals()) {
    WindowSolverResidual res;
    res.cost = r.cost.get();
    res.loss = r.loss;
    res.first_block = static_cast<int>(problem.block_indices.size());
    res.num_blocks = static_cast<int>(r.blocks.size());
    for (double* b : r.blocks) {
      const int i = index_of(b);
      problem.block_indices.push_back(i);
    }
    if (r.anchor < 0) {
      res.prior = &w->prior();
    } else {
      res.tangent = dynamic_cast<const TangentJacobians*>(r.cost.get());
    }
    problem.residuals.push_back(res);
  }
  return problem;
}

class WindowSolverCeresTest
    : public ::testing::TestWithParam<ceres::TrustRegionStrategyType> {};

// The same visual window (Huber and TolerantLoss, a marginalisation prior,
// poses on the manifold) solved to convergence by this solver and by
// ceres::Solve ends at the same minimum.
TEST_P(WindowSolverCeresTest, ConvergesToTheMinimumCeresFinds) {
  InverseDepthWindow ours, theirs;
  WindowSolverOptions options;
  options.trust_region = GetParam();
  options.max_iterations = 100;
  options.function_tolerance = 1e-14;
  options.gradient_tolerance = 1e-16;
  options.parameter_tolerance = 1e-14;
  const ceres::Solver::Summary summary = SolveWindow(ProblemOf(&ours), options);
  ASSERT_NE(summary.termination_type, ceres::FAILURE) << summary.message;

  const std::unique_ptr<ceres::Problem> problem =
      theirs.CeresProblem(theirs.All());
  ceres::Solver::Options ceres_options;
  ceres_options.linear_solver_type = ceres::DENSE_SCHUR;
  ceres_options.trust_region_strategy_type = GetParam();
  ceres_options.max_num_iterations = 100;
  ceres_options.function_tolerance = 1e-14;
  ceres_options.gradient_tolerance = 1e-16;
  ceres_options.parameter_tolerance = 1e-14;
  ceres::Solver::Summary reference;
  ceres::Solve(ceres_options, problem.get(), &reference);
  ASSERT_TRUE(reference.IsSolutionUsable()) << reference.BriefReport();

  // The same objective (losses included) at the same start ...
  EXPECT_NEAR(summary.initial_cost, reference.initial_cost,
              1e-12 * reference.initial_cost);
  // ... and the same minimum, well below the start.
  EXPECT_LT(reference.final_cost, 0.5 * reference.initial_cost);
  EXPECT_NEAR(summary.final_cost, reference.final_cost,
              1e-9 * reference.final_cost);
  for (int i = 0; i < InverseDepthWindow::kPoses; ++i) {
    for (int c = 0; c < 7; ++c) {
      EXPECT_NEAR(ours.Pose(i)[c], theirs.Pose(i)[c], 1e-7) << i << " " << c;
    }
  }
  for (int k = 0; k < InverseDepthWindow::kLandmarks; ++k) {
    EXPECT_NEAR(*ours.Rho(k), *theirs.Rho(k), 1e-7) << k;
  }
}

INSTANTIATE_TEST_SUITE_P(Strategies, WindowSolverCeresTest,
                         ::testing::Values(ceres::DOGLEG,
                                           ceres::LEVENBERG_MARQUARDT));

// One solver serving problems of different sizes (its buffers re-used) gives
// bit for bit what a fresh solver gives.
TEST(WindowSolver, ReusedSolverGivesTheSameBitsAsAFreshOne) {
  InverseDepthWindow a, b;
  std::mt19937 rng(3);
  LinearProblem small(rng);
  WindowSolverOptions options;
  WindowSolver reused;
  *reused.NewProblem() = small.Problem();
  reused.Solve(options);
  *reused.NewProblem() = ProblemOf(&a);
  const ceres::Solver::Summary s1 = reused.Solve(options);
  const ceres::Solver::Summary s2 = SolveWindow(ProblemOf(&b), options);
  EXPECT_EQ(s1.final_cost, s2.final_cost);
  EXPECT_EQ(s1.iterations.size(), s2.iterations.size());
  for (int i = 0; i < InverseDepthWindow::kPoses; ++i) {
    EXPECT_EQ(std::memcmp(a.Pose(i), b.Pose(i), 7 * sizeof(double)), 0) << i;
  }
  for (int k = 0; k < InverseDepthWindow::kLandmarks; ++k) {
    EXPECT_EQ(*a.Rho(k), *b.Rho(k)) << k;
  }
}

TEST(WindowSolver, StopsAtTheIterationLimitLikeCeres) {
  InverseDepthWindow w;
  WindowSolverOptions options;
  options.max_iterations = 2;
  options.function_tolerance = 0.0;
  const ceres::Solver::Summary s = SolveWindow(ProblemOf(&w), options);
  EXPECT_EQ(s.termination_type, ceres::NO_CONVERGENCE);
  EXPECT_EQ(s.iterations.size(), 3u);  // iteration 0 and two steps
  EXPECT_LT(s.final_cost, s.initial_cost);
}

TEST(WindowSolver, BoundHoldsTheSolution) {
  double x = 0.0;
  const ScalarTestFactor pull(5.0, false);
  WindowSolverProblem problem;
  WindowSolverBlock b{&x, 1};
  b.lower = -1.0;
  b.upper = 1.0;
  problem.blocks.push_back(b);
  problem.block_indices.push_back(0);
  problem.residuals.push_back({&pull, nullptr, 0, 1});
  WindowSolverOptions options;
  options.max_iterations = 20;
  SolveWindow(problem, options);
  EXPECT_EQ(x, 1.0);
}

TEST(WindowSolver, EvaluationFailureAtTheStartIsAFailure) {
  double x = 0.25;
  const ScalarTestFactor failing(5.0, true);
  WindowSolverProblem problem;
  problem.blocks.push_back({&x, 1});
  problem.block_indices.push_back(0);
  problem.residuals.push_back({&failing, nullptr, 0, 1});
  const ceres::Solver::Summary s = SolveWindow(problem, {});
  EXPECT_EQ(s.termination_type, ceres::FAILURE);
  EXPECT_EQ(x, 0.25);
}

TEST(WindowSolver, EliminatedBlocksMustBeIndependentScalars) {
  Eigen::Vector3d p(0, 0, 0);
  double s = 0.0, t = 1.0;
  const LinearTestFactor f(Eigen::Matrix<double, 2, 3>::Ones(),
                           Eigen::Vector2d::Ones(), Eigen::Vector2d::Zero());
  WindowSolverProblem problem;
  WindowSolverBlock vector_block{p.data(), 3};
  vector_block.eliminated = true;  // size 3: not a scalar
  problem.blocks.push_back(vector_block);
  WindowSolverBlock scalar{&s, 1};
  scalar.eliminated = true;
  problem.blocks.push_back(scalar);
  problem.block_indices = {0, 1};
  problem.residuals.push_back({&f, nullptr, 0, 2});
  EXPECT_THROW(SolveWindow(problem, {}), std::invalid_argument);
  problem.blocks[0].eliminated = false;
  EXPECT_NO_THROW(SolveWindow(problem, {}));

  // Two eliminated scalars in one residual are not independent.
  const PairTestFactor pair;
  WindowSolverBlock other{&t, 1};
  other.eliminated = true;
  problem.blocks.push_back(other);
  problem.block_indices.insert(problem.block_indices.end(), {1, 2});
  problem.residuals.push_back({&pair, nullptr, 2, 2});
  EXPECT_THROW(SolveWindow(problem, {}), std::invalid_argument);
}

}  // namespace
}  // namespace vio
