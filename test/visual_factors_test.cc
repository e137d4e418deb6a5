// The four visual factors against numeric differentiation (our tangent-space
// check and ceres::GradientChecker), their weighting, and their behaviour in
// degenerate geometry. Every test runs once per factor.

#include <ceres/gradient_checker.h>
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <random>

#include "factors/check/factor_cases.h"
#include "factors/check/jacobian_check.h"
#include "factors/check/visual_scene.h"
#include "factors/inverse_depth_chain.h"
#include "factors/tangent_jacobians.h"

namespace vio {
namespace {

using RowMajorMatrix =
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// Residual and ambient Jacobians of an instance at its stored blocks.
struct Evaluation {
  bool ok = false;
  Eigen::VectorXd r;
  std::vector<RowMajorMatrix> jacobians;
};

Evaluation Evaluate(const FactorInstance& f) {
  Evaluation e;
  const int m = f.cost->num_residuals();
  e.r.resize(m);
  std::vector<const double*> params;
  std::vector<double*> jac_ptrs;
  e.jacobians.resize(f.blocks.size());
  for (size_t b = 0; b < f.blocks.size(); ++b) {
    params.push_back(f.blocks[b].data());
    e.jacobians[b].setConstant(m, f.blocks[b].size(), -12345.0);
    jac_ptrs.push_back(e.jacobians[b].data());
  }
  e.ok = f.cost->Evaluate(params.data(), e.r.data(), jac_ptrs.data());
  return e;
}

bool AllFinite(const Evaluation& e) {
  bool finite = e.r.allFinite();
  for (const auto& J : e.jacobians) finite = finite && J.allFinite();
  return finite;
}

bool AllJacobiansZero(const Evaluation& e) {
  for (const auto& J : e.jacobians) {
    if (!J.isZero(0.0)) return false;
  }
  return true;
}

class VisualFactorTest : public ::testing::TestWithParam<size_t> {
 protected:
  const VisualFactorKind& kind() const {
    return VisualFactorKinds()[GetParam()];
  }
  FactorCase MakeCase(VisualGeometry geometry) const {
    return MakeVisualCase(kind(), geometry);
  }
  // Runs `trials` states of the case and expects every block to match.
  void ExpectJacobiansMatch(VisualGeometry geometry, int trials,
                            unsigned seed) const {
    const FactorCase c = MakeCase(geometry);
    std::mt19937 rng(seed);
    for (int t = 0; t < trials; ++t) {
      const FactorInstance f = c.sample(rng);
      std::vector<BlockJacobianError> errors;
      ASSERT_TRUE(CompareJacobians(f, JacobianCheckOptions(), &errors));
      for (const auto& e : errors) {
        EXPECT_LE(e.max_rel_error, c.tolerance)
            << c.name << " block " << e.block << " trial " << t;
      }
    }
  }
};

TEST_P(VisualFactorTest, JacobiansMatchNumericDiffOnMixedStates) {
  // Half realistic, half near a degenerate case (see MakeReprojectionCase).
  ExpectJacobiansMatch(VisualGeometry::kMixed, 200, 42);
}

TEST_P(VisualFactorTest, JacobiansMatchNumericDiffNearDegenerateStates) {
  ExpectJacobiansMatch(VisualGeometry::kFarPoint, 100, 1);
  ExpectJacobiansMatch(VisualGeometry::kNegativeDepth, 100, 2);
  ExpectJacobiansMatch(VisualGeometry::kNearTargetCamera, 100, 3);
}

TEST_P(VisualFactorTest, GradientCheckerWithPoseManifoldAgrees) {
  const FactorCase c = MakeCase(VisualGeometry::kRealistic);
  std::mt19937 rng(7);
  for (int t = 0; t < 50; ++t) {
    const FactorInstance f = c.sample(rng);
    std::vector<const ceres::Manifold*> manifolds;
    std::vector<const double*> params;
    for (size_t b = 0; b < f.blocks.size(); ++b) {
      manifolds.push_back(f.manifolds[b].get());
      params.push_back(f.blocks[b].data());
    }
    // GradientChecker differentiates in the ambient space with Ridders'
    // method. Its default first step (1 % of each coordinate) pushes a pose's
    // quaternion so far off the unit sphere that the rotation of a point
    // metres away is no longer in the linear range and the extrapolation
    // stops early; 1e-4 keeps it there.
    ceres::NumericDiffOptions options;
    options.ridders_relative_initial_step_size = 1e-4;
    const ceres::GradientChecker checker(f.cost.get(), &manifolds, options);
    ceres::GradientChecker::ProbeResults results;
    EXPECT_TRUE(checker.Probe(params.data(), 1e-6, &results))
        << c.name << " trial " << t << "\n"
        << results.error_log;
  }
}

// What a tangent-space solver receives (factors/tangent_jacobians.h) is
// exactly what Ceres gets from the ambient Jacobian: J_amb * PlusJacobian,
// with the same residual. On mixed states: the degenerate ones (inactive,
// zero Jacobians) included.
TEST_P(VisualFactorTest, TangentJacobiansEqualAmbientTimesPlusJacobian) {
  const FactorCase c = MakeCase(VisualGeometry::kMixed);
  std::mt19937 rng(5);
  for (int t = 0; t < 100; ++t) {
    const FactorInstance f = c.sample(rng);
    const auto* tangent = dynamic_cast<const TangentJacobians*>(f.cost.get());
    ASSERT_NE(tangent, nullptr) << c.name;
    const Evaluation ambient = Evaluate(f);
    ASSERT_TRUE(ambient.ok);
    const int m = f.cost->num_residuals();
    std::vector<const double*> params;
    std::vector<RowMajorMatrix> J(f.blocks.size());
    std::vector<double*> ptrs;
    for (size_t b = 0; b < f.blocks.size(); ++b) {
      params.push_back(f.blocks[b].data());
      const int size = static_cast<int>(f.blocks[b].size());
      J[b].setConstant(m, f.manifolds[b] ? f.manifolds[b]->TangentSize() : size,
                       -12345.0);
      ptrs.push_back(J[b].data());
    }
    Eigen::VectorXd r(m);
    ASSERT_TRUE(tangent->EvaluateTangent(params.data(), r.data(), ptrs.data()));
    EXPECT_EQ(r, ambient.r) << c.name << " trial " << t;
    for (size_t b = 0; b < f.blocks.size(); ++b) {
      RowMajorMatrix expected = ambient.jacobians[b];
      if (f.manifolds[b]) {
        RowMajorMatrix plus(f.blocks[b].size(), f.manifolds[b]->TangentSize());
        f.manifolds[b]->PlusJacobian(f.blocks[b].data(), plus.data());
        expected = ambient.jacobians[b] * plus;
      }
      const double scale = std::max(1.0, expected.cwiseAbs().maxCoeff());
      EXPECT_LT((J[b] - expected).cwiseAbs().maxCoeff(), 1e-12 * scale)
          << c.name << " block " << b << " trial " << t;
    }
  }
}

TEST_P(VisualFactorTest, ResidualOnlyEvaluationGivesTheSameBits) {
  // The window solver's candidate costs evaluate without Jacobians (a
  // shorter path in the two-frame factors); a trajectory that must not
  // change needs the very same residual bits as with Jacobians.
  for (VisualGeometry geometry :
       {VisualGeometry::kMixed, VisualGeometry::kFarPoint,
        VisualGeometry::kNegativeDepth, VisualGeometry::kNearTargetCamera}) {
    const FactorCase c = MakeCase(geometry);
    std::mt19937 rng(21);
    for (int t = 0; t < 200; ++t) {
      const FactorInstance f = c.sample(rng);
      const Evaluation with_jacobians = Evaluate(f);
      std::vector<const double*> params;
      for (const auto& block : f.blocks) params.push_back(block.data());
      Eigen::VectorXd r(f.cost->num_residuals());
      ASSERT_EQ(f.cost->Evaluate(params.data(), r.data(), nullptr),
                with_jacobians.ok);
      EXPECT_EQ(r, with_jacobians.r) << c.name << " trial " << t;
    }
  }
}

TEST_P(VisualFactorTest, ResidualIsProjectionErrorInUnitsOfSigma) {
  std::mt19937 rng(11);
  for (int t = 0; t < 20; ++t) {
    VisualScene s = SampleVisualScene(rng, VisualGeometry::kRealistic,
                                      kind().target, kind().timed, 0.0);
    EXPECT_LT(Evaluate(kind().make(s)).r.norm(), 1e-9) << "noise-free";
    // Moving the measurement by d on the normalised plane changes the
    // residual by -sqrt_info * d.
    const Eigen::Vector2d d(2e-3, -1e-3);
    s.obs_j.xy += d;
    const Evaluation e = Evaluate(kind().make(s));
    EXPECT_TRUE(e.r.isApprox(-s.sqrt_info * d, 1e-6)) << e.r.transpose();
  }
}

TEST_P(VisualFactorTest, PointAtTargetCameraCentreIsFiniteAndInactive) {
  std::mt19937 rng(12);
  for (int t = 0; t < 20; ++t) {
    VisualScene s = SampleVisualScene(rng, VisualGeometry::kRealistic,
                                      kind().target, kind().timed);
    // Put the target camera's centre on the landmark.
    const Eigen::Isometry3d T_w_ca =
        IsometryFromBlock(s.pose_i) * IsometryFromBlock(s.extrinsic0);
    const Eigen::Vector2d xy_i =
        s.obs_i.xy - (s.t_d - s.obs_i.t_d_at_stamp) * s.obs_i.velocity;
    Eigen::Isometry3d T_w_c = TargetCameraPose(s, kind().target);
    T_w_c.translation() = T_w_ca * (xy_i.homogeneous() / s.rho);
    SetTargetCameraPose(T_w_c, kind().target, &s);
    ASSERT_LT(TargetPoint(s, kind().target).norm(), 1e-9);

    const Evaluation e = Evaluate(kind().make(s));
    EXPECT_TRUE(e.ok);
    EXPECT_TRUE(AllFinite(e));
    EXPECT_TRUE(AllJacobiansZero(e));
  }
}

TEST_P(VisualFactorTest, PointBehindTargetCameraIsFiniteAndInactive) {
  std::mt19937 rng(13);
  for (int t = 0; t < 20; ++t) {
    VisualScene s = SampleVisualScene(rng, VisualGeometry::kRealistic,
                                      kind().target, kind().timed);
    // Turn the target camera around its x axis: the point is now behind it.
    const Eigen::Isometry3d T_w_c =
        TargetCameraPose(s, kind().target) *
        Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX());
    SetTargetCameraPose(T_w_c, kind().target, &s);
    ASSERT_LT(TargetPoint(s, kind().target).z(), 0.0);

    const Evaluation e = Evaluate(kind().make(s));
    EXPECT_TRUE(e.ok);
    EXPECT_TRUE(AllFinite(e));
    EXPECT_TRUE(AllJacobiansZero(e));
    // Clamped, not hidden: far larger than any inlier.
    EXPECT_GT(e.r.norm(), 100.0);
  }
}

TEST_P(VisualFactorTest, ZeroTinyAndNegativeInverseDepthsAreFinite) {
  std::mt19937 rng(14);
  for (double rho : {0.0, 1e-300, -1e-300, -1e-12, 1e-12, -0.5, -10.0, 1e6}) {
    VisualScene s = SampleVisualScene(rng, VisualGeometry::kRealistic,
                                      kind().target, kind().timed);
    s.rho = rho;
    const Evaluation e = Evaluate(kind().make(s));
    EXPECT_TRUE(e.ok) << "rho " << rho;
    EXPECT_TRUE(AllFinite(e)) << "rho " << rho;
  }
}

TEST_P(VisualFactorTest, ResidualIsContinuousAtInfinity) {
  // rho -> 0 is the limit of ever farther points, not a special case: the
  // residual at rho = 0 is the limit of the residuals at rho = 1e-k.
  std::mt19937 rng(15);
  VisualScene s = SampleVisualScene(rng, VisualGeometry::kFarPoint,
                                    kind().target, kind().timed);
  s.rho = 0.0;
  const Eigen::VectorXd r_inf = Evaluate(kind().make(s)).r;
  s.rho = 1e-9;
  EXPECT_TRUE(Evaluate(kind().make(s)).r.isApprox(r_inf, 1e-6));
}

INSTANTIATE_TEST_SUITE_P(AllVisualFactors, VisualFactorTest,
                         ::testing::Range<size_t>(0,
                                                  VisualFactorKinds().size()),
                         [](const ::testing::TestParamInfo<size_t>& info) {
                           return VisualFactorKinds()[info.param].name;
                         });

TEST(ProjectResidual, ClampsAndZeroesBelowMinProjectiveDepth) {
  const Eigen::Vector2d xy(0.1, -0.2);
  const ProjectedResidual above = ProjectResidual(
      Eigen::Vector3d(0.3, 0.1, 2.0 * kMinProjectiveDepth), xy, 300.0);
  EXPECT_TRUE(above.active);
  EXPECT_FALSE(above.d_r_d_h.isZero(0.0));
  const ProjectedResidual below =
      ProjectResidual(Eigen::Vector3d(0.3, 0.1, -5.0), xy, 300.0);
  EXPECT_FALSE(below.active);
  EXPECT_TRUE(below.d_r_d_h.isZero(0.0));
  EXPECT_TRUE(below.r.isApprox(
      300.0 * (Eigen::Vector2d(0.3, 0.1) / kMinProjectiveDepth - xy)));
}

}  // namespace
}  // namespace vio
