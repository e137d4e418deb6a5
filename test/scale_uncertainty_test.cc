// The relative std of a window's spread (estimator/scale_uncertainty.h): two
// problems whose answer is known in closed form, and the spread of Monte
// Carlo solutions against the prediction.

#include "estimator/scale_uncertainty.h"

#include <ceres/autodiff_cost_function.h>
#include <ceres/ceres.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "factors/pose_manifold.h"
#include "testing/pose_test_factors.h"
#include "test/testing/spread.h"

namespace vio {
namespace {

using testing::Matrix6d;

// Positions p_k = s q_k (rotation identity), q_k on a tilted ellipse.
std::vector<Eigen::Vector3d> Shape(int n) {
  std::vector<Eigen::Vector3d> q;
  for (int k = 0; k < n; ++k) {
    const double a = 0.4 * k;
    q.emplace_back(3.0 * std::cos(a), 2.0 * std::sin(a), 0.3 * std::sin(2 * a));
  }
  return q;
}

using vio::testing::Spread;

// r = (t - s q) / sigma on a pose (7) and a scale (1).
struct ScaledPositionResidual {
  template <typename T>
  bool operator()(const T* pose, const T* s, T* r) const {
    for (int i = 0; i < 3; ++i) r[i] = (pose[i] - s[0] * q[i]) / sigma;
    return true;
  }
  Eigen::Vector3d q;
  double sigma;
};

// r = (s - s_m) / sigma.
struct ScalePriorResidual {
  template <typename T>
  bool operator()(const T* s, T* r) const {
    r[0] = (s[0] - s_m) / sigma;
    return true;
  }
  double s_m;
  double sigma;
};

// The problem: every pose's rotation held by a prior, its position either
// measured directly (position_sigma) or tied to the common scale
// (tie_sigma > 0) whose prior is scale_sigma. Positions measured at
// `measured`; poses start there.
struct Problem {
  std::vector<std::array<double, 7>> poses;
  double scale = 1.0;
  PoseManifold manifold;
  std::unique_ptr<ceres::Problem> problem;

  Problem(const std::vector<Eigen::Vector3d>& shape,
          const std::vector<Eigen::Vector3d>& measured, double position_sigma,
          double tie_sigma, double scale_measured, double scale_sigma) {
    ceres::Problem::Options o;
    o.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    problem = std::make_unique<ceres::Problem>(o);
    poses.resize(shape.size());
    for (size_t k = 0; k < shape.size(); ++k) {
      poses[k] = {measured[k].x(), measured[k].y(), measured[k].z(), 0, 0, 0, 1};
      problem->AddParameterBlock(poses[k].data(), 7, &manifold);
      Matrix6d W = Matrix6d::Zero();
      W.bottomRightCorner<3, 3>() = 1e3 * Eigen::Matrix3d::Identity();
      if (position_sigma > 0.0) {
        W.topLeftCorner<3, 3>() = Eigen::Matrix3d::Identity() / position_sigma;
      }
      problem->AddResidualBlock(
          new testing::PosePriorTestFactor(measured[k],
                                           Eigen::Quaterniond::Identity(), W),
          nullptr, poses[k].data());
      if (tie_sigma > 0.0) {
        problem->AddResidualBlock(
            new ceres::AutoDiffCostFunction<ScaledPositionResidual, 3, 7, 1>(
                new ScaledPositionResidual{shape[k], tie_sigma}),
            nullptr, poses[k].data(), &scale);
      }
    }
    if (tie_sigma > 0.0) {
      scale = scale_measured;
      problem->AddResidualBlock(
          new ceres::AutoDiffCostFunction<ScalePriorResidual, 1, 1>(
              new ScalePriorResidual{scale_measured, scale_sigma}),
          nullptr, &scale);
    }
  }
  std::vector<const double*> Blocks() const {
    std::vector<const double*> b;
    for (const auto& p : poses) b.push_back(p.data());
    return b;
  }
  std::vector<Eigen::Vector3d> Positions() const {
    std::vector<Eigen::Vector3d> p;
    for (const auto& x : poses) p.emplace_back(x[0], x[1], x[2]);
    return p;
  }
  void Solve() {
    ceres::Solver::Options o;
    o.max_num_iterations = 20;
    o.function_tolerance = 1e-12;
    o.gradient_tolerance = 1e-14;
    o.parameter_tolerance = 1e-12;
    ceres::Solver::Summary summary;
    ceres::Solve(o, problem.get(), &summary);
  }
};

TEST(ScaleUncertainty, IndependentPositionsGiveSigmaOverRootNSpread) {
  // Var(S) = sum_k |g_k|^2 sigma^2 = sigma^2 / n: relative sigma / (sqrt(n) S).
  const std::vector<Eigen::Vector3d> shape = Shape(11);
  const double sigma = 0.02;
  Problem p(shape, shape, sigma, 0.0, 1.0, 0.0);
  const double expected = sigma / (std::sqrt(11.0) * Spread(shape));
  EXPECT_NEAR(RelativeSpreadSigma(p.problem.get(), p.Blocks()), expected,
              1e-6 * expected);
}

TEST(ScaleUncertainty, ACommonScaleGivesItsOwnRelativeSigma) {
  // Positions tied tightly to one scale s with a 5 % prior and nothing
  // else: the spread is s S(q), so its relative sigma is the prior's (and
  // the ties add sigma_t^2 / (n S^2), negligible here). The cross terms
  // between frames are nearly all of it.
  const std::vector<Eigen::Vector3d> shape = Shape(11);
  Problem p(shape, shape, 0.0, 1e-4, 1.0, 0.05);
  EXPECT_NEAR(RelativeSpreadSigma(p.problem.get(), p.Blocks()), 0.05, 5e-4);
}

TEST(ScaleUncertainty, MatchesTheSpreadOfMonteCarloSolutions) {
  // Each position measured with 5 cm of noise, all tied (1 cm) to a common
  // scale measured to 3 %: solved afresh for 400 noise draws, the spread of
  // the solutions' S has the predicted relative std.
  const std::vector<Eigen::Vector3d> shape = Shape(11);
  const double position_sigma = 0.05, tie_sigma = 0.01, scale_sigma = 0.03;
  std::mt19937 rng(42);
  std::normal_distribution<double> n01(0.0, 1.0);
  std::vector<double> spreads;
  double predicted = -1.0;
  for (int draw = 0; draw < 400; ++draw) {
    std::vector<Eigen::Vector3d> measured;
    for (const auto& q : shape) {
      measured.push_back(q + position_sigma * Eigen::Vector3d(n01(rng), n01(rng),
                                                              n01(rng)));
    }
    Problem p(shape, measured, position_sigma, tie_sigma,
              1.0 + scale_sigma * n01(rng), scale_sigma);
    p.Solve();
    spreads.push_back(Spread(p.Positions()));
    if (draw == 0) predicted = RelativeSpreadSigma(p.problem.get(), p.Blocks());
  }
  double mean = 0.0;
  for (double s : spreads) mean += s;
  mean /= static_cast<double>(spreads.size());
  double var = 0.0;
  for (double s : spreads) var += (s - mean) * (s - mean);
  const double empirical =
      std::sqrt(var / static_cast<double>(spreads.size() - 1)) / mean;
  ASSERT_GT(predicted, 0.0);
  // 400 draws: the std of a std estimate is ~1/sqrt(2 * 400) = 3.5 %.
  EXPECT_NEAR(empirical / predicted, 1.0, 0.12)
      << "empirical " << empirical << ", predicted " << predicted;
}

TEST(ScaleUncertainty, AnUnconstrainedDirectionGivesNoAnswer) {
  // Positions tied to the scale, whose prior carries no information (a
  // sigma of 1e300): scaling everything costs nothing, Ceres finds the
  // information rank deficient.
  const std::vector<Eigen::Vector3d> shape = Shape(5);
  Problem p(shape, shape, 0.0, 1e-3, 1.0, 1e300);
  EXPECT_LT(RelativeSpreadSigma(p.problem.get(), p.Blocks()), 0.0);
}

}  // namespace
}  // namespace vio
