// The window solver's kept-factor solve (WindowSolverOptions::
// kept_factor_pcg, WindowLinearization::SolveDampedWithKeptFactor): a
// linearisation after the first solved by conjugate gradients preconditioned
// with the earlier Cholesky factor gives the exact (freshly factored) step,
// and a factor too far from the system is not trusted: a fresh one is made.
// The problem is the one that made the option worth having: world points
// (3-vectors left in the dense reduced system) tied to each other by a dense
// marginalisation prior, beside poses and eliminated inverse depths.

#include <ceres/loss_function.h>
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <vector>

#include "estimator/window_linearization.h"
#include "estimator/window_solver.h"
#include "factors/marginalization_prior.h"
#include "factors/world_point_factor.h"
#include "test/testing/inverse_depth_window.h"

namespace vio {
namespace {

using testing::InverseDepthWindow;

constexpr int kPoints = 16;

Eigen::Isometry3d IsometryOf(const double* x) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::Quaterniond(x[6], x[3], x[4], x[5]).toRotationMatrix();
  T.translation() = Eigen::Vector3d(x[0], x[1], x[2]);
  return T;
}

// InverseDepthWindow (5 poses, 40 inverse depths, a prior on two poses) with
// kPoints world points 3-6 m ahead of pose 0, each seen by every pose
// (WorldPointReprojectionFactor, Huber), and a second prior over pose 1 and
// all the points with a dense random information (every point coupled with
// every other, as the marginalisation leaves them). The points start 5 cm
// away from where their sightings put them. Deterministic.
class PointWindow {
 public:
  PointWindow() {
    std::mt19937 rng(11);
    std::normal_distribution<double> n(0.0, 1.0);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const Eigen::Isometry3d T_b_c = IsometryOf(window_.Extrinsic());
    std::array<Eigen::Vector3d, kPoints> seen;
    for (int k = 0; k < kPoints; ++k) {
      const double z = 3.0 + 1.5 * (u(rng) + 1.0);
      seen[k] = IsometryOf(window_.Pose(0)) * T_b_c *
                Eigen::Vector3d(0.4 * u(rng) * z, 0.3 * u(rng) * z, z);
      for (int i = 0; i < InverseDepthWindow::kPoses; ++i) {
        const Eigen::Vector3d p_c =
            (IsometryOf(window_.Pose(i)) * T_b_c).inverse() * seen[k];
        const Eigen::Vector2d xy =
            p_c.head<2>() / p_c.z() + Eigen::Vector2d(n(rng), n(rng)) / 460.0;
        factors_.push_back(
            std::make_unique<WorldPointReprojectionFactor>(xy, 460.0 / 1.5));
      }
      const Eigen::Vector3d start =
          seen[k] + 0.05 * Eigen::Vector3d(n(rng), n(rng), n(rng)).normalized();
      for (int d = 0; d < 3; ++d) points_[k][d] = start[d];
    }
    std::vector<PriorBlock> blocks;
    const double* pose1 = window_.Pose(1);
    blocks.push_back({PriorBlockKind::kPose, {pose1, pose1 + 7}});
    for (int k = 0; k < kPoints; ++k) {
      blocks.push_back({PriorBlockKind::kEuclidean,
                        {seen[k].x(), seen[k].y(), seen[k].z()}});
    }
    const int m = 6 + 3 * kPoints;
    Eigen::MatrixXd A(m, m);
    for (int r = 0; r < m; ++r) {
      for (int c = 0; c < m; ++c) A(r, c) = 0.3 * u(rng);
    }
    // About 2 cm on each point, 1 cm and 0.3 deg on the pose, correlated.
    Eigen::VectorXd sigma = Eigen::VectorXd::Constant(m, 0.02);
    sigma.head<6>() << 0.01, 0.01, 0.01, 0.005, 0.005, 0.005;
    Eigen::MatrixXd info = sigma.cwiseInverse().asDiagonal();
    info = info * (Eigen::MatrixXd::Identity(m, m) + A * A.transpose()) * info;
    Eigen::VectorXd r0(m);
    for (int r = 0; r < m; ++r) r0[r] = 0.5 * n(rng);
    prior_ = std::make_unique<MarginalizationPrior>(
        blocks, Eigen::MatrixXd(info.llt().matrixU()), r0);
  }

  // The window solver's problem over all of it (poses on the manifold, the
  // extrinsic constant, inverse depths eliminated, points reduced).
  WindowSolverProblem Problem() {
    WindowSolverProblem p;
    std::vector<const double*> order;
    auto index_of = [&](double* b, int size, bool pose) {
      for (size_t i = 0; i < order.size(); ++i) {
        if (order[i] == b) return static_cast<int>(i);
      }
      order.push_back(b);
      WindowSolverBlock block;
      block.values = b;
      block.size = size;
      block.manifold = pose ? window_.pose_manifold() : nullptr;
      block.constant = b == window_.Extrinsic();
      block.eliminated = size == 1;
      p.blocks.push_back(block);
      return static_cast<int>(order.size() - 1);
    };
    auto add = [&](const ceres::CostFunction* cost,
                   const ceres::LossFunction* loss,
                   const std::vector<double*>& blocks) {
      WindowSolverResidual r;
      r.cost = cost;
      r.loss = loss;
      r.first_block = static_cast<int>(p.block_indices.size());
      r.num_blocks = static_cast<int>(blocks.size());
      for (double* b : blocks) {
        const bool pose = window_.IsPose(b);
        bool point = false;
        for (auto& q : points_) point = point || q.data() == b;
        p.block_indices.push_back(index_of(b, pose ? 7 : point ? 3 : 1, pose));
      }
      p.residuals.push_back(r);
      return &p.residuals.back();
    };
    for (const InverseDepthWindow::Residual& r : window_.residuals()) {
      WindowSolverResidual* res = add(r.cost.get(), r.loss, r.blocks);
      if (r.anchor < 0) {
        res->prior = &window_.prior();
      } else {
        res->tangent = dynamic_cast<const TangentJacobians*>(r.cost.get());
      }
    }
    int f = 0;
    for (int k = 0; k < kPoints; ++k) {
      for (int i = 0; i < InverseDepthWindow::kPoses; ++i, ++f) {
        add(factors_[f].get(), window_.huber(),
            {window_.Pose(i), window_.Extrinsic(), points_[k].data()})
            ->tangent = factors_[f].get();
      }
    }
    std::vector<double*> blocks = {window_.Pose(1)};
    for (auto& q : points_) blocks.push_back(q.data());
    add(prior_.get(), nullptr, blocks)->prior = prior_.get();
    return p;
  }

  std::vector<double> State() {
    std::vector<double> x;
    for (int i = 0; i < InverseDepthWindow::kPoses; ++i) {
      x.insert(x.end(), window_.Pose(i), window_.Pose(i) + 7);
    }
    for (int k = 0; k < InverseDepthWindow::kLandmarks; ++k) {
      x.push_back(*window_.Rho(k));
    }
    for (auto& q : points_) x.insert(x.end(), q.begin(), q.end());
    return x;
  }

 private:
  InverseDepthWindow window_;
  std::array<std::array<double, 3>, kPoints> points_{};
  std::vector<std::unique_ptr<WorldPointReprojectionFactor>> factors_;
  std::unique_ptr<MarginalizationPrior> prior_;
};

constexpr double kGaussNewtonDamping = 1e-8;  // the dogleg's smallest mu

// Two Gauss-Newton steps from the start, the second factored; the third
// linearisation is solved with that factor by conjugate gradients: no new
// factor, and the step agrees with the exact one (a fresh Cholesky factor of
// the same system) to 1e-5 of its length, coordinate by coordinate to 1e-5
// of the largest, inverse depths included. (The first step, from 5 cm and
// half a degree off, changes the system too much for 8 iterations: that is
// the fallback below.)
TEST(WindowSolverKeptFactor, RelinearisedStepEqualsTheExactOne) {
  PointWindow w;
  const WindowSolverProblem problem = w.Problem();
  WindowLinearization lin;
  lin.SetUp(problem);
  Eigen::VectorXd dx;
  for (int step = 0; step < 2; ++step) {
    ASSERT_TRUE(lin.Linearize());
    ASSERT_TRUE(lin.SolveDamped(kGaussNewtonDamping, &dx));
    double cost = 0.0;
    ASSERT_TRUE(lin.CandidateCost(dx, &cost));
    ASSERT_LT(cost, lin.cost());
    lin.Accept();
  }
  ASSERT_TRUE(lin.Linearize());
  Eigen::VectorXd inexact, exact;
  ASSERT_TRUE(lin.SolveDampedWithKeptFactor(kGaussNewtonDamping, &inexact));
  const WindowLinearization::SolveCounts counts = lin.solve_counts();
  EXPECT_EQ(counts.factorizations, 2);
  EXPECT_EQ(counts.pcg_solves, 1);
  EXPECT_EQ(counts.pcg_fallbacks, 0);
  EXPECT_GE(counts.pcg_iterations, 1);
  EXPECT_LE(counts.pcg_iterations, WindowLinearization::kMaxPcgIterations);
  ASSERT_TRUE(lin.SolveDamped(kGaussNewtonDamping, &exact));
  ASSERT_EQ(inexact.size(), exact.size());
  EXPECT_GT(exact.norm(), 0.0);
  EXPECT_LT((inexact - exact).norm(), 1e-5 * exact.norm());
  EXPECT_LT((inexact - exact).lpNorm<Eigen::Infinity>(),
            1e-5 * exact.lpNorm<Eigen::Infinity>());
  std::printf(
      "kept factor: %d iteration(s), |dx - dx_exact| / |dx_exact| "
      "= %.2e\n",
      counts.pcg_iterations, (inexact - exact).norm() / exact.norm());
}

// A factor of a system far from the one to solve (the Gauss-Newton damping
// against a Levenberg-Marquardt damping of 10: the preconditioned matrix no
// longer near the identity) does not converge within the iteration limit:
// the system is factored afresh and the step is the exact one, bit for bit.
TEST(WindowSolverKeptFactor, StaleFactorFallsBackToAFreshOne) {
  PointWindow w;
  const WindowSolverProblem problem = w.Problem();
  WindowLinearization lin;
  lin.SetUp(problem);
  ASSERT_TRUE(lin.Linearize());
  Eigen::VectorXd dx, exact;
  ASSERT_TRUE(lin.SolveDamped(kGaussNewtonDamping, &dx));
  ASSERT_TRUE(lin.SolveDampedWithKeptFactor(10.0, &dx));
  const WindowLinearization::SolveCounts counts = lin.solve_counts();
  EXPECT_EQ(counts.pcg_fallbacks, 1);
  EXPECT_EQ(counts.pcg_solves, 0);
  EXPECT_EQ(counts.factorizations, 2);
  ASSERT_TRUE(lin.SolveDamped(10.0, &exact));
  EXPECT_EQ(dx, exact);
}

// Without a factor of this problem (right after SetUp) the system is
// factored: the same bits as SolveDamped.
TEST(WindowSolverKeptFactor, FirstSolveOfAProblemFactors) {
  PointWindow w;
  const WindowSolverProblem problem = w.Problem();
  WindowLinearization lin;
  lin.SetUp(problem);
  ASSERT_TRUE(lin.Linearize());
  Eigen::VectorXd dx, exact;
  ASSERT_TRUE(lin.SolveDampedWithKeptFactor(kGaussNewtonDamping, &dx));
  EXPECT_EQ(lin.solve_counts().factorizations, 1);
  EXPECT_EQ(lin.solve_counts().pcg_solves, 0);
  ASSERT_TRUE(lin.SolveDamped(kGaussNewtonDamping, &exact));
  EXPECT_EQ(dx, exact);
}

// The whole solve (dogleg, 4 iterations as shipped) with and without the
// option ends at the same state: the largest difference of any value is
// below 1e-7 (positions in metres, quaternion parts, inverse depths in 1/m;
// the steps are centimetres) and the costs agree to 1e-9. Not bit for bit:
// a solve that only fell back to fresh factors would give the same bits.
TEST(WindowSolverKeptFactor, SolveEndsWhereTheFactoredOneDoes) {
  PointWindow a, b;
  WindowSolverOptions options;
  options.function_tolerance = 1e-3;
  const ceres::Solver::Summary exact = SolveWindow(a.Problem(), options);
  options.kept_factor_pcg = true;
  const ceres::Solver::Summary kept = SolveWindow(b.Problem(), options);
  ASSERT_NE(exact.termination_type, ceres::FAILURE) << exact.message;
  ASSERT_NE(kept.termination_type, ceres::FAILURE) << kept.message;
  EXPECT_GE(exact.iterations.size(), 3u);  // more than one linearisation
  EXPECT_EQ(kept.iterations.size(), exact.iterations.size());
  const std::vector<double> xa = a.State(), xb = b.State();
  double largest = 0.0;
  for (size_t i = 0; i < xa.size(); ++i) {
    largest = std::max(largest, std::abs(xa[i] - xb[i]));
  }
  EXPECT_LT(largest, 1e-7);
  EXPECT_GT(largest, 0.0);
  EXPECT_NEAR(kept.final_cost, exact.final_cost, 1e-9 * exact.final_cost);
}

}  // namespace
}  // namespace vio
