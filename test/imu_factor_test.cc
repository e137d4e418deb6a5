#include "factors/imu_factor.h"

#include <ceres/gradient_checker.h>
#include <ceres/problem.h>
#include <ceres/solver.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <vector>

#include "factors/check/factor_cases.h"
#include "factors/check/jacobian_check.h"
#include "factors/pose_manifold.h"
#include "geometry/so3.h"
#include "test/testing/analytic_trajectory.h"
#include "test/testing/imu_residual_functor.h"

namespace vio {
namespace {

constexpr double kGravity = 9.81;
constexpr int kStates = 200;

std::vector<const double*> Pointers(const FactorInstance& f) {
  std::vector<const double*> out;
  for (const auto& b : f.blocks) out.push_back(b.data());
  return out;
}

// Row-major Jacobians of every block, as Ceres returns them.
using RowMajor =
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// Tangent Jacobians J_ambient * PlusJacobian of `cost` at the instance.
std::vector<Eigen::MatrixXd> TangentJacobians(const ceres::CostFunction& cost,
                                              const FactorInstance& f) {
  std::vector<RowMajor> ambient;
  std::vector<double*> ptrs;
  for (const auto& b : f.blocks) {
    ambient.emplace_back(15, b.size());
  }
  for (auto& a : ambient) ptrs.push_back(a.data());
  Vector15d r;
  EXPECT_TRUE(cost.Evaluate(Pointers(f).data(), r.data(), ptrs.data()));
  std::vector<Eigen::MatrixXd> out;
  for (size_t b = 0; b < f.blocks.size(); ++b) {
    if (f.manifolds[b]) {
      RowMajor plus(7, 6);
      f.manifolds[b]->PlusJacobian(f.blocks[b].data(), plus.data());
      out.push_back(ambient[b] * plus);
    } else {
      out.push_back(ambient[b]);
    }
  }
  return out;
}

TEST(ImuFactor, JacobiansMatchNumericDiffAt200RandomStates) {
  const FactorCase imu = MakeImuFactorCase();
  std::mt19937 rng(7);
  for (int i = 0; i < kStates; ++i) {
    const FactorInstance f = imu.sample(rng);
    std::vector<BlockJacobianError> errors;
    ASSERT_TRUE(CompareJacobians(f, JacobianCheckOptions(), &errors));
    for (const auto& e : errors) {
      EXPECT_LE(e.max_rel_error, imu.tolerance) << e.block << ", state " << i;
    }
  }
}

TEST(ImuFactor, GradientCheckerWithPoseManifoldAgrees) {
  // Ceres' own numeric Jacobians as a second opinion: it differentiates in
  // the ambient space and maps through PoseManifold::PlusJacobian. Its
  // verdict compares entry by entry, which fails on entries that are zero up
  // to rounding (1e-16 next to 1e5 in the same block, from the dense square
  // root information), so the comparison here is relative to each block's
  // largest entry, as in jacobian_check. Ridders' default first step, 1e-2
  // of each quaternion coefficient, takes the ambient point far off the unit
  // sphere and its extrapolation then misses by up to 1.5e-4 on the rotation
  // rows (measured); a first step of 1e-4 keeps it local.
  const FactorCase imu = MakeImuFactorCase();
  const PoseManifold pose_manifold;
  const std::vector<const ceres::Manifold*> manifolds = {
      &pose_manifold, nullptr, &pose_manifold, nullptr};
  std::mt19937 rng(8);
  for (int i = 0; i < 20; ++i) {
    const FactorInstance f = imu.sample(rng);
    ceres::NumericDiffOptions numeric_diff;
    numeric_diff.ridders_relative_initial_step_size = 1e-4;
    const ceres::GradientChecker checker(f.cost.get(), &manifolds,
                                         numeric_diff);
    ceres::GradientChecker::ProbeResults results;
    checker.Probe(Pointers(f).data(), 1e-5, &results);
    ASSERT_TRUE(results.return_value);
    for (size_t b = 0; b < f.blocks.size(); ++b) {
      const Eigen::MatrixXd& numeric = results.local_numeric_jacobians[b];
      const double error =
          (results.local_jacobians[b] - numeric).cwiseAbs().maxCoeff();
      EXPECT_LE(error, 1e-5 * numeric.cwiseAbs().maxCoeff())
          << f.block_names[b] << ", state " << i;
    }
  }
}

TEST(ImuFactor, AutoDiffOfTheSameResidualAgreesAt200RandomStates) {
  const FactorCase imu = MakeImuFactorCase();
  std::mt19937 rng(9);
  for (int i = 0; i < kStates; ++i) {
    const FactorInstance f = imu.sample(rng);
    const auto& factor = static_cast<const ImuFactor&>(*f.cost);
    const testing::ImuAutoDiffCost autodiff(new testing::ImuResidualFunctor(
        factor.preintegrated(), kGravity, factor.sqrt_information()));
    Vector15d r_analytic, r_auto;
    ASSERT_TRUE(
        factor.Evaluate(Pointers(f).data(), r_analytic.data(), nullptr));
    ASSERT_TRUE(autodiff.Evaluate(Pointers(f).data(), r_auto.data(), nullptr));
    EXPECT_LE((r_analytic - r_auto).norm(), 1e-9 * (1.0 + r_auto.norm()));
    const auto J_analytic = TangentJacobians(factor, f);
    const auto J_auto = TangentJacobians(autodiff, f);
    for (size_t b = 0; b < J_auto.size(); ++b) {
      const double scale = J_auto[b].cwiseAbs().maxCoeff();
      EXPECT_LE((J_analytic[b] - J_auto[b]).cwiseAbs().maxCoeff(), 1e-9 * scale)
          << f.block_names[b] << ", state " << i;
    }
  }
}

// States of the analytic trajectory at t [s] with constant biases.
struct TrueState {
  std::vector<double> pose, speed_bias;
};

TrueState StateAt(const testing::AnalyticTrajectory& traj, double t,
                  const Eigen::Vector3d& b_a, const Eigen::Vector3d& b_g) {
  const Eigen::Vector3d p = traj.Position(t), v = traj.Velocity(t);
  const Eigen::Quaterniond q = traj.Rotation(t);
  return {{p.x(), p.y(), p.z(), q.x(), q.y(), q.z(), q.w()},
          {v.x(), v.y(), v.z(), b_a.x(), b_a.y(), b_a.z(), b_g.x(), b_g.y(),
           b_g.z()}};
}

class ImuFactorOnTrajectory : public ::testing::Test {
 protected:
  const testing::AnalyticTrajectory traj_;
  const Eigen::Vector3d b_a_{0.12, -0.05, 0.2};
  const Eigen::Vector3d b_g_{0.01, -0.02, 0.005};
  const int64_t t0_ns_ = 1000000000 + 1700000;
  const int64_t t1_ns_ = t0_ns_ + 500000000;
  const std::vector<ImuSample> samples_ =
      traj_.Samples(900000000, 1600000000, 5000000, b_a_, b_g_);
  TrueState state_i_ = StateAt(traj_, 1e-9 * t0_ns_, b_a_, b_g_);
  TrueState state_j_ = StateAt(traj_, 1e-9 * t1_ns_, b_a_, b_g_);

  std::vector<const double*> Params() const {
    return {state_i_.pose.data(), state_i_.speed_bias.data(),
            state_j_.pose.data(), state_j_.speed_bias.data()};
  }
};

TEST_F(ImuFactorOnTrajectory, ResidualAtTrueStatesIsTheDiscretisationError) {
  // With the true biases as linearisation point, the unweighted residual is
  // the preintegration's discretisation error (errors p 2.5e-6 m,
  // theta 1.5e-7 rad, v 4.6e-6 m/s, within the bound stated in
  // imu_preintegration_test.cc), far inside the noise: chi^2 << 1.
  const ImuPreintegration pre(t0_ns_, t1_ns_, samples_, b_a_, b_g_, ImuNoise(),
                              PreintegrationOptions());
  const ImuFactor factor(pre.result(), kGravity);
  Vector15d r, weighted;
  ASSERT_TRUE(factor.UnweightedResidual(Params().data(), &r));
  ASSERT_TRUE(factor.Evaluate(Params().data(), weighted.data(), nullptr));
  EXPECT_LT(r.segment<3>(kImuP).norm(), 5e-6);
  EXPECT_LT(r.segment<3>(kImuR).norm(), 5e-7);
  EXPECT_LT(r.segment<3>(kImuV).norm(), 1e-5);
  EXPECT_EQ(r.tail<6>().norm(), 0.0);
  EXPECT_LT(weighted.squaredNorm(), 0.01);
}

TEST_F(ImuFactorOnTrajectory,
       BiasCorrectionKeepsResidualSmallOffTheLinearisation) {
  // Linearised at biases off by (0.03 m/s^2, 0.003 rad/s) per axis, the
  // first-order correction brings the residual at the truth back to the
  // discretisation level plus a second-order term.
  const Eigen::Vector3d off_a = Eigen::Vector3d::Constant(0.03);
  const Eigen::Vector3d off_g = Eigen::Vector3d::Constant(0.003);
  const ImuPreintegration pre(t0_ns_, t1_ns_, samples_, b_a_ + off_a,
                              b_g_ + off_g, ImuNoise(),
                              PreintegrationOptions());
  const ImuFactor factor(pre.result(), kGravity);
  Vector15d corrected;
  ASSERT_TRUE(factor.UnweightedResidual(Params().data(), &corrected));
  // Without the correction the same states would miss by the full effect.
  const ImuDelta uncorrected = pre.delta();
  const ImuDelta exact = ImuPreintegration(t0_ns_, t1_ns_, samples_, b_a_, b_g_,
                                           ImuNoise(), PreintegrationOptions())
                             .delta();
  const double missed_v = (uncorrected.v - exact.v).norm();
  EXPECT_GT(missed_v, 1e-2);
  EXPECT_LT(corrected.segment<3>(kImuV).norm(), 0.01 * missed_v);
  EXPECT_LT(corrected.segment<3>(kImuR).norm(), 1e-5);
}

TEST_F(ImuFactorOnTrajectory, SolverRecoversStateJFromPerturbedStart) {
  // End to end (as OKVIS' TestImuError): state i fixed, state j perturbed,
  // Ceres with the analytic Jacobians and PoseManifold returns to the truth.
  const ImuPreintegration pre(t0_ns_, t1_ns_, samples_, b_a_, b_g_, ImuNoise(),
                              PreintegrationOptions());
  const TrueState truth_j = state_j_;
  state_j_.pose[0] += 0.3;
  state_j_.pose[2] -= 0.2;
  const Eigen::Quaterniond q =
      Eigen::Quaterniond(Eigen::Vector4d(state_j_.pose.data() + 3)) *
      ExpQuaternion(Eigen::Vector3d(0.1, -0.2, 0.15));
  std::copy(q.coeffs().data(), q.coeffs().data() + 4, state_j_.pose.data() + 3);
  state_j_.speed_bias[0] += 0.5;
  state_j_.speed_bias[4] += 0.05;
  ceres::Problem problem;
  problem.AddResidualBlock(new ImuFactor(pre.result(), kGravity), nullptr,
                           state_i_.pose.data(), state_i_.speed_bias.data(),
                           state_j_.pose.data(), state_j_.speed_bias.data());
  problem.SetManifold(state_i_.pose.data(), new PoseManifold);
  problem.SetManifold(state_j_.pose.data(), new PoseManifold);
  problem.SetParameterBlockConstant(state_i_.pose.data());
  problem.SetParameterBlockConstant(state_i_.speed_bias.data());
  ceres::Solver::Options options;
  options.max_num_iterations = 20;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  EXPECT_EQ(summary.termination_type, ceres::CONVERGENCE);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(state_j_.pose[k], truth_j.pose[k], 1e-5);
    EXPECT_NEAR(state_j_.speed_bias[k], truth_j.speed_bias[k], 1e-5);
  }
  const Eigen::Quaterniond q_est(Eigen::Vector4d(state_j_.pose.data() + 3));
  const Eigen::Quaterniond q_true(Eigen::Vector4d(truth_j.pose.data() + 3));
  EXPECT_LT(Log(q_true.conjugate() * q_est).norm(), 1e-6);
}

TEST_F(ImuFactorOnTrajectory, EvaluateReturnsFalseOnNonFiniteState) {
  const ImuPreintegration pre(t0_ns_, t1_ns_, samples_, b_a_, b_g_, ImuNoise(),
                              PreintegrationOptions());
  const ImuFactor factor(pre.result(), kGravity);
  state_j_.speed_bias[7] = std::numeric_limits<double>::quiet_NaN();
  Vector15d r;
  EXPECT_FALSE(factor.Evaluate(Params().data(), r.data(), nullptr));
}

TEST(ImuFactor, ConstructorRejectsBadGravityAndCovariance) {
  PreintegratedImu pre;
  pre.sum_dt = 0.1;
  pre.covariance = Matrix15d::Identity();
  EXPECT_THROW(ImuFactor(pre, 0.0), std::invalid_argument);
  EXPECT_THROW(ImuFactor(pre, std::nan("")), std::invalid_argument);
  pre.covariance(4, 4) = -1.0;
  EXPECT_THROW(ImuFactor(pre, kGravity), std::invalid_argument);
}

}  // namespace
}  // namespace vio
