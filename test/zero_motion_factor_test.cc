#include "factors/zero_motion_factor.h"

#include <ceres/ceres.h>
#include <ceres/gradient_checker.h>
#include <gtest/gtest.h>

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

FactorCase ZeroMotionCase() {
  for (const FactorCase& c : AllFactorCases()) {
    if (c.name == "zero_motion") return c;
  }
  ADD_FAILURE() << "zero_motion is not registered";
  return MakeZeroMotionFactorCase();
}

std::vector<const double*> Pointers(const FactorInstance& f) {
  std::vector<const double*> p;
  for (const auto& b : f.blocks) p.push_back(b.data());
  return p;
}

TEST(ZeroMotionFactor, JacobianMatchesNumericDiffAt200States) {
  const FactorCase c = ZeroMotionCase();
  std::mt19937 rng(11);
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

TEST(ZeroMotionFactor, GradientCheckerAgrees) {
  const FactorCase c = ZeroMotionCase();
  std::mt19937 rng(12);
  ceres::NumericDiffOptions numeric;
  numeric.ridders_relative_initial_step_size = 1e-4;
  // The checker's error is relative per entry: the rotation block's
  // off-diagonal entries near identity are 1e-8 beside diagonal entries of
  // 500 (1 / sigma) and carry 1e-11 of absolute differentiation noise, a few
  // 1e-3 relative. The tangent-space check above is the precise proof.
  for (int trial = 0; trial < 20; ++trial) {
    const FactorInstance f = c.sample(rng);
    std::vector<const ceres::Manifold*> manifolds;
    for (const auto& m : f.manifolds) manifolds.push_back(m.get());
    ceres::GradientChecker checker(f.cost.get(), &manifolds, numeric);
    ceres::GradientChecker::ProbeResults results;
    EXPECT_TRUE(checker.Probe(Pointers(f).data(), 5e-3, &results))
        << "trial " << trial << ": " << results.error_log;
  }
}

// Independently of the code: two poses 3 mm and 0.2 deg apart about z and a
// velocity of 1 cm/s give, over the sigmas, exactly these whitened values.
TEST(ZeroMotionFactor, ResidualIsTheWhitenedMotion) {
  const ZeroMotionFactor f(0.002, 0.001, 0.005);
  const double angle = 0.2 * M_PI / 180.0;
  const Eigen::Quaterniond q_i(
      Eigen::AngleAxisd(1.0, Eigen::Vector3d::UnitX()));
  const Eigen::Quaterniond q_j = q_i * Eigen::Quaterniond(Eigen::AngleAxisd(
                                           angle, Eigen::Vector3d::UnitZ()));
  const double pose_i[7] = {1, 2, 3, q_i.x(), q_i.y(), q_i.z(), q_i.w()};
  const double pose_j[7] = {1.003, 2, 3, q_j.x(), q_j.y(), q_j.z(), q_j.w()};
  const double sb_j[9] = {0, 0.01, 0, 0.5, 0.5, 0.5, 0.1, 0.1, 0.1};
  const double* params[] = {pose_i, pose_j, sb_j};
  Eigen::Matrix<double, 9, 1> r;
  ASSERT_TRUE(f.Evaluate(params, r.data(), nullptr));
  Eigen::Matrix<double, 9, 1> expected;
  expected << 1.5, 0, 0, 0, 0, angle / 0.001, 0, 2.0, 0;
  EXPECT_LT((r - expected).norm(), 1e-9) << r.transpose();
}

// In a least-squares problem the factor pulls a drifted pose back onto the
// still one and the velocity to zero, and leaves the biases alone.
TEST(ZeroMotionFactor, SolvingPullsTheSecondPoseOntoTheFirst) {
  double pose_i[7] = {0, 0, 1, 0, 0, 0, 1};
  const Eigen::Quaterniond q(Eigen::AngleAxisd(0.05, Eigen::Vector3d::UnitY()));
  double pose_j[7] = {0.2, -0.1, 1.05, q.x(), q.y(), q.z(), q.w()};
  double sb_j[9] = {0.3, 0.2, -0.1, 0.05, 0, 0, 0.01, 0, 0};
  ceres::Problem::Options po;
  po.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(po);
  PoseManifold manifold;
  problem.AddParameterBlock(pose_i, 7, &manifold);
  problem.AddParameterBlock(pose_j, 7, &manifold);
  problem.SetParameterBlockConstant(pose_i);
  problem.AddResidualBlock(new ZeroMotionFactor(0.002, 0.002, 0.005), nullptr,
                           pose_i, pose_j, sb_j);
  ceres::Solver::Options o;
  o.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(o, &problem, &summary);
  EXPECT_LT((Eigen::Vector3d(pose_j) - Eigen::Vector3d(pose_i)).norm(), 1e-8);
  EXPECT_LT(Eigen::Quaterniond(pose_j + 3)
                .angularDistance(Eigen::Quaterniond::Identity()),
            1e-9);
  EXPECT_LT(Eigen::Vector3d(sb_j).norm(), 1e-8);
  EXPECT_EQ(sb_j[3], 0.05);  // b_a untouched (zero Jacobian)
}

TEST(ZeroMotionFactor, BadSigmaThrowsAndNonFiniteStateFails) {
  EXPECT_THROW(ZeroMotionFactor(0.0, 1.0, 1.0), std::invalid_argument);
  EXPECT_THROW(ZeroMotionFactor(1.0, -1.0, 1.0), std::invalid_argument);
  EXPECT_THROW(ZeroMotionFactor(1.0, 1.0, std::nan("")), std::invalid_argument);
  const ZeroMotionFactor f(0.002, 0.002, 0.005);
  const double pose[7] = {0, 0, 0, 0, 0, 0, 1};
  const double bad[9] = {
      std::numeric_limits<double>::quiet_NaN(), 0, 0, 0, 0, 0, 0, 0, 0};
  const double* params[] = {pose, pose, bad};
  double r[9];
  EXPECT_FALSE(f.Evaluate(params, r, nullptr));
}

}  // namespace
}  // namespace vio
