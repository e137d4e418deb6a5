// The world-point reprojection factor (factors/world_point_factor.h): its
// Jacobians against numeric differentiation, its tangent Jacobians against
// the ambient ones, its residual against a closed form (and against the
// inverse-depth factor on the same landmark), and a point behind the camera.

#include "factors/world_point_factor.h"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <random>
#include <vector>

#include "factors/check/factor_cases.h"
#include "factors/check/jacobian_check.h"
#include "factors/check/visual_scene.h"
#include "factors/reprojection_factor.h"

namespace vio {
namespace {

using RowMajorMatrix =
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

Eigen::Vector2d Residual(const FactorInstance& f) {
  std::vector<const double*> params;
  for (const auto& b : f.blocks) params.push_back(b.data());
  Eigen::Vector2d r;
  EXPECT_TRUE(f.cost->Evaluate(params.data(), r.data(), nullptr));
  return r;
}

TEST(WorldPointReprojectionFactor, JacobiansMatchNumericDiff) {
  const FactorCase c = MakeWorldPointReprojectionCase();
  std::mt19937 rng(42);
  for (int t = 0; t < 300; ++t) {
    const FactorInstance f = c.sample(rng);
    std::vector<BlockJacobianError> errors;
    ASSERT_TRUE(CompareJacobians(f, JacobianCheckOptions(), &errors));
    for (const auto& e : errors) {
      EXPECT_LE(e.max_rel_error, c.tolerance) << e.block << " trial " << t;
    }
  }
}

TEST(WorldPointReprojectionFactor, TangentJacobiansEqualAmbientTimesPlus) {
  const FactorCase c = MakeWorldPointReprojectionCase();
  std::mt19937 rng(5);
  for (int t = 0; t < 100; ++t) {
    const FactorInstance f = c.sample(rng);
    const auto* tangent = dynamic_cast<const TangentJacobians*>(f.cost.get());
    ASSERT_NE(tangent, nullptr);
    std::vector<const double*> params;
    std::vector<RowMajorMatrix> ambient(3), J(3);
    std::vector<double*> ambient_ptrs, tangent_ptrs;
    for (size_t b = 0; b < 3; ++b) {
      params.push_back(f.blocks[b].data());
      const int size = static_cast<int>(f.blocks[b].size());
      ambient[b].setConstant(2, size, -12345.0);
      J[b].setConstant(2, f.manifolds[b] ? 6 : size, -12345.0);
      ambient_ptrs.push_back(ambient[b].data());
      tangent_ptrs.push_back(J[b].data());
    }
    Eigen::Vector2d r_amb, r_tan;
    ASSERT_TRUE(
        f.cost->Evaluate(params.data(), r_amb.data(), ambient_ptrs.data()));
    ASSERT_TRUE(tangent->EvaluateTangent(params.data(), r_tan.data(),
                                         tangent_ptrs.data()));
    EXPECT_EQ(r_amb, r_tan);
    for (size_t b = 0; b < 3; ++b) {
      RowMajorMatrix expected = ambient[b];
      if (f.manifolds[b]) {
        RowMajorMatrix plus(7, 6);
        f.manifolds[b]->PlusJacobian(f.blocks[b].data(), plus.data());
        expected = ambient[b] * plus;
      }
      const double scale = std::max(1.0, expected.cwiseAbs().maxCoeff());
      EXPECT_LT((J[b] - expected).cwiseAbs().maxCoeff(), 1e-12 * scale)
          << "block " << b << " trial " << t;
    }
  }
}

TEST(WorldPointReprojectionFactor, ResidualIsTheClosedFormProjectionError) {
  std::mt19937 rng(11);
  for (int t = 0; t < 40; ++t) {
    const bool camera1 = t % 2 == 1;
    const VisualScene s =
        SampleVisualScene(rng, VisualGeometry::kRealistic,
                          camera1 ? VisualTarget::kStereoOtherFrame
                                  : VisualTarget::kMonoOtherFrame,
                          /*timed=*/false, 1.5);
    // r = sqrt_info (pi(T_c_w p_w) - xy), T_c_w = (T_w_b T_b_c)^-1.
    const Eigen::Isometry3d T_w_c =
        IsometryFromBlock(s.pose_j) *
        IsometryFromBlock(camera1 ? s.extrinsic1 : s.extrinsic0);
    const Eigen::Vector3d p_c = T_w_c.inverse() * SceneWorldPoint(s);
    const Eigen::Vector2d expected =
        s.sqrt_info * (p_c.head<2>() / p_c.z() - s.obs_j.xy);
    const Eigen::Vector2d r = Residual(MakeWorldPointReprojection(s, camera1));
    EXPECT_TRUE(r.isApprox(expected, 1e-9)) << r.transpose();
    // The noise-free sighting gives a zero residual.
    VisualScene clean = s;
    clean.obs_j.xy = p_c.head<2>() / p_c.z();
    EXPECT_LT(Residual(MakeWorldPointReprojection(clean, camera1)).norm(),
              1e-9);
    if (camera1) continue;
    // The same landmark as an inverse depth in keyframe i: the same error.
    const ReprojectionFactor inverse_depth(s.obs_i.xy, s.obs_j.xy, s.sqrt_info);
    const double* params[] = {s.pose_i.data(), s.pose_j.data(),
                              s.extrinsic0.data(), &s.rho};
    Eigen::Vector2d r_rho;
    ASSERT_TRUE(inverse_depth.Evaluate(params, r_rho.data(), nullptr));
    EXPECT_TRUE(r.isApprox(r_rho, 1e-9));
  }
}

TEST(WorldPointReprojectionFactor, PointBehindTheCameraIsFiniteAndInactive) {
  std::mt19937 rng(13);
  for (int t = 0; t < 20; ++t) {
    VisualScene s = SampleVisualScene(rng, VisualGeometry::kRealistic,
                                      VisualTarget::kMonoOtherFrame, false);
    const Eigen::Isometry3d T_w_c =
        TargetCameraPose(s, VisualTarget::kMonoOtherFrame) *
        Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX());
    SetTargetCameraPose(T_w_c, VisualTarget::kMonoOtherFrame, &s);
    FactorInstance f = MakeWorldPointReprojection(s, false);
    std::vector<const double*> params;
    std::vector<RowMajorMatrix> J(3);
    std::vector<double*> ptrs;
    for (size_t b = 0; b < 3; ++b) {
      params.push_back(f.blocks[b].data());
      J[b].setConstant(2, static_cast<int>(f.blocks[b].size()), -1.0);
      ptrs.push_back(J[b].data());
    }
    Eigen::Vector2d r;
    ASSERT_TRUE(f.cost->Evaluate(params.data(), r.data(), ptrs.data()));
    EXPECT_TRUE(r.allFinite());
    EXPECT_GT(r.norm(), 100.0);
    for (const auto& j : J) EXPECT_TRUE(j.isZero(0.0));
  }
}

TEST(WorldPointReprojectionFactor, FirstEstimateJacobiansAreTakenThere) {
  // keep_point_fej: the residual at p_w, the Jacobians those of the plain
  // factor at p_w_first.
  const FactorCase c = MakeWorldPointReprojectionCase();
  std::mt19937 rng(17);
  for (int t = 0; t < 50; ++t) {
    const FactorInstance f = c.sample(rng);
    const Eigen::Vector2d xy(0.05, -0.02);
    const WorldPointReprojectionFactor plain(xy, 300.0);
    std::vector<double> first = f.blocks[2];
    first[0] += 0.03;
    first[2] -= 0.05;
    const WorldPointReprojectionFactor fej(xy, 300.0, first.data());
    const double* at_p[] = {f.blocks[0].data(), f.blocks[1].data(),
                            f.blocks[2].data()};
    const double* at_first[] = {f.blocks[0].data(), f.blocks[1].data(),
                                first.data()};
    std::vector<RowMajorMatrix> J_fej(3), J_first(3);
    std::vector<double*> p_fej, p_first;
    for (size_t b = 0; b < 3; ++b) {
      const int size = static_cast<int>(f.blocks[b].size());
      J_fej[b].setZero(2, size);
      J_first[b].setZero(2, size);
      p_fej.push_back(J_fej[b].data());
      p_first.push_back(J_first[b].data());
    }
    Eigen::Vector2d r_fej, r_plain, r_first;
    ASSERT_TRUE(fej.Evaluate(at_p, r_fej.data(), p_fej.data()));
    ASSERT_TRUE(plain.Evaluate(at_p, r_plain.data(), nullptr));
    ASSERT_TRUE(plain.Evaluate(at_first, r_first.data(), p_first.data()));
    EXPECT_EQ(r_fej, r_plain);
    for (size_t b = 0; b < 3; ++b) EXPECT_EQ(J_fej[b], J_first[b]) << b;
  }
}

}  // namespace
}  // namespace vio
