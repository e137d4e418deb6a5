#include "estimator/pose_covariance.h"

#include <ceres/ceres.h>
#include <gtest/gtest.h>

#include <random>

#include "factors/pose_manifold.h"
#include "geometry/so3.h"
#include "testing/pose_test_factors.h"

namespace vio {
namespace {

using testing::Matrix6d;

std::array<double, 7> PoseValues(const Eigen::Vector3d& t,
                                 const Eigen::Quaterniond& q) {
  return {t.x(), t.y(), t.z(), q.x(), q.y(), q.z(), q.w()};
}

Matrix6d RandomSqrtInformation(std::mt19937* rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Matrix6d W = Matrix6d::Zero();
  for (int r = 0; r < 6; ++r) {
    W(r, r) = 20.0 + 30.0 * std::abs(u(*rng));
    for (int c = r + 1; c < 6; ++c) W(r, c) = 5.0 * u(*rng);
  }
  return W;
}

TEST(PoseCovariance, OfAPosePriorIsItsInverseInformation) {
  // r = W [t - t_m; Log(q_m^-1 q)] at t = t_m, q = q_m: J = W, so the
  // covariance is (W^T W)^-1 exactly.
  std::mt19937 rng(42);
  const Matrix6d W = RandomSqrtInformation(&rng);
  const Eigen::Vector3d t(1.0, -2.0, 0.5);
  const Eigen::Quaterniond q = ExpQuaternion(Eigen::Vector3d(0.3, -1.2, 2.0));
  std::array<double, 7> pose = PoseValues(t, q);
  PoseManifold manifold;
  ceres::Problem::Options o;
  o.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(o);
  problem.AddParameterBlock(pose.data(), 7, &manifold);
  problem.AddResidualBlock(new testing::PosePriorTestFactor(t, q, W), nullptr,
                           pose.data());
  Matrix6d covariance;
  ASSERT_TRUE(PoseCovariance(&problem, pose.data(), &covariance));
  const Matrix6d expected = (W.transpose() * W).inverse();
  EXPECT_LT((covariance - expected).norm(), 1e-9 * expected.norm());
}

TEST(PoseCovariance, MatchesTheSpreadOfMonteCarloSolutions) {
  // Pose a has a prior, pose b a relative measurement from a. Re-solving
  // with fresh measurement noise many times, the spread of b's solutions
  // (on the tangent at the truth) is b's covariance.
  std::mt19937 rng(7);
  const Matrix6d W_a = RandomSqrtInformation(&rng);
  const Matrix6d W_ab = RandomSqrtInformation(&rng);
  const Eigen::Vector3d t_a(0.5, 0.2, 1.0), t_ab(2.0, -1.0, 0.3);
  const Eigen::Quaterniond q_a = ExpQuaternion(Eigen::Vector3d(0.2, 0.4, 1.0));
  const Eigen::Quaterniond q_ab =
      ExpQuaternion(Eigen::Vector3d(-0.5, 0.3, 0.8));
  const Eigen::Vector3d t_b = t_a + q_a * t_ab;
  const Eigen::Quaterniond q_b = q_a * q_ab;
  std::normal_distribution<double> normal(0.0, 1.0);
  auto noise = [&](const Matrix6d& W) {
    Eigen::Matrix<double, 6, 1> n;
    for (int k = 0; k < 6; ++k) n[k] = normal(rng);
    return Eigen::Matrix<double, 6, 1>(W.inverse() * n);
  };
  PoseManifold manifold;
  Matrix6d spread = Matrix6d::Zero();
  Matrix6d claimed = Matrix6d::Zero();
  constexpr int kRuns = 400;
  for (int run = 0; run < kRuns; ++run) {
    const Eigen::Matrix<double, 6, 1> na = noise(W_a), nab = noise(W_ab);
    std::array<double, 7> a = PoseValues(t_a, q_a), b = PoseValues(t_b, q_b);
    ceres::Problem::Options o;
    o.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    ceres::Problem problem(o);
    problem.AddParameterBlock(a.data(), 7, &manifold);
    problem.AddParameterBlock(b.data(), 7, &manifold);
    problem.AddResidualBlock(
        new testing::PosePriorTestFactor(
            t_a + na.head<3>(), q_a * ExpQuaternion(na.tail<3>()), W_a),
        nullptr, a.data());
    problem.AddResidualBlock(
        new testing::RelativePoseTestFactor(
            t_ab + nab.head<3>(), q_ab * ExpQuaternion(nab.tail<3>()), W_ab),
        nullptr, a.data(), b.data());
    ceres::Solver::Options solver;
    solver.max_num_iterations = 20;
    ceres::Solver::Summary summary;
    ceres::Solve(solver, &problem, &summary);
    Matrix6d covariance;
    ASSERT_TRUE(PoseCovariance(&problem, b.data(), &covariance));
    claimed += covariance / kRuns;
    Eigen::Matrix<double, 6, 1> e;
    e.head<3>() = Eigen::Vector3d(b.data()) - t_b;
    e.tail<3>() = Log(q_b.conjugate() * Eigen::Quaterniond(b.data() + 3));
    spread += e * e.transpose() / kRuns;
  }
  // 400 samples: the sample variances are within ~15 % (3 sigma of a
  // chi-square with 400 dof is 21 %); compare the whitened spread.
  const Eigen::LLT<Matrix6d> llt(claimed);
  const Matrix6d L_inv = Matrix6d(llt.matrixL()).inverse();
  const Matrix6d whitened = L_inv * spread * L_inv.transpose();
  EXPECT_NEAR(whitened.trace() / 6.0, 1.0, 0.12);
  EXPECT_LT((whitened - Matrix6d::Identity()).cwiseAbs().maxCoeff(), 0.25);
}

}  // namespace
}  // namespace vio
