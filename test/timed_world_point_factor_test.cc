// The world-point reprojection factor with a time offset
// (factors/timed_world_point_factor.h): its ambient and tangent Jacobians
// against numeric differentiation, its residual against a closed form and
// against the plain world-point factor at t_d = t_d_k, the shifted sighting
// against a simulated moving camera's projection at the shifted time, a
// point behind the camera, and the first-estimate Jacobians.

#include "factors/timed_world_point_factor.h"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "factors/check/factor_cases.h"
#include "factors/check/jacobian_check.h"
#include "factors/check/visual_scene.h"
#include "factors/world_point_factor.h"
#include "geometry/so3.h"

namespace vio {
namespace {

using RowMajorMatrix =
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// Evaluates f at its blocks; Jacobians (ambient, one matrix per block) when
// J is not null.
Eigen::Vector2d Evaluate(const ceres::CostFunction& f,
                         const std::vector<std::vector<double>>& blocks,
                         std::vector<RowMajorMatrix>* J = nullptr) {
  std::vector<const double*> params;
  std::vector<double*> ptrs;
  for (size_t b = 0; b < blocks.size(); ++b) {
    params.push_back(blocks[b].data());
    if (J != nullptr) {
      (*J)[b].setConstant(2, static_cast<int>(blocks[b].size()), -12345.0);
      ptrs.push_back((*J)[b].data());
    }
  }
  Eigen::Vector2d r;
  EXPECT_TRUE(f.Evaluate(params.data(), r.data(),
                         J != nullptr ? ptrs.data() : nullptr));
  return r;
}

// tools/jacobian_check runs it (AllFactorCases is its table).
TEST(TimedWorldPointReprojectionFactor, IsRegisteredInJacobianCheck) {
  int found = 0;
  for (const FactorCase& c : AllFactorCases()) {
    found += c.name == "world_point_td" ? 1 : 0;
  }
  EXPECT_EQ(found, 1);
}

TEST(TimedWorldPointReprojectionFactor, JacobiansMatchNumericDiff) {
  const FactorCase c = MakeTimedWorldPointReprojectionCase();
  std::mt19937 rng(42);
  int tangent_rows = 0;
  for (int t = 0; t < 300; ++t) {
    const FactorInstance f = c.sample(rng);
    ASSERT_EQ(f.blocks.size(), 4u);
    std::vector<BlockJacobianError> errors;
    ASSERT_TRUE(CompareJacobians(f, JacobianCheckOptions(), &errors));
    for (const auto& e : errors) {
      EXPECT_LE(e.max_rel_error, c.tolerance) << e.block << " trial " << t;
      if (e.block.find("(tangent)") != std::string::npos) ++tangent_rows;
    }
  }
  // Both the ambient (Evaluate) and the tangent (EvaluateTangent) Jacobians
  // of all four blocks were compared.
  EXPECT_EQ(tangent_rows, 4 * 300);
}

// r = sqrt_info (pi(T_c_w p_w) - (xy - (t_d - t_d_k) v)), written out here.
TEST(TimedWorldPointReprojectionFactor, ResidualIsTheShiftedProjectionError) {
  std::mt19937 rng(11);
  for (int t = 0; t < 40; ++t) {
    const bool camera1 = t % 2 == 1;
    const VisualScene s =
        SampleVisualScene(rng, VisualGeometry::kRealistic,
                          camera1 ? VisualTarget::kStereoOtherFrame
                                  : VisualTarget::kMonoOtherFrame,
                          /*timed=*/true, 1.5);
    const Eigen::Isometry3d T_w_c =
        IsometryFromBlock(s.pose_j) *
        IsometryFromBlock(camera1 ? s.extrinsic1 : s.extrinsic0);
    const Eigen::Vector3d p_c = T_w_c.inverse() * SceneWorldPoint(s);
    FactorInstance f = MakeTimedWorldPointReprojection(s, camera1);
    for (const double t_d : {s.t_d, s.t_d + 0.004, -0.011}) {
      f.blocks[3][0] = t_d;
      const Eigen::Vector2d xy_shifted =
          s.obs_j.xy - (t_d - s.obs_j.t_d_at_stamp) * s.obs_j.velocity;
      const Eigen::Vector2d expected =
          s.sqrt_info * (p_c.head<2>() / p_c.z() - xy_shifted);
      const Eigen::Vector2d r = Evaluate(*f.cost, f.blocks);
      EXPECT_TRUE(r.isApprox(expected, 1e-9)) << r.transpose();
    }
  }
}

// At t_d = t_d_k nothing is shifted: exactly the plain factor's residual
// and, on the blocks they share, its Jacobians.
TEST(TimedWorldPointReprojectionFactor, AtTheStampOffsetItIsThePlainFactor) {
  const FactorCase c = MakeTimedWorldPointReprojectionCase();
  std::mt19937 rng(23);
  for (int t = 0; t < 60; ++t) {
    FactorInstance f = c.sample(rng);
    const TimedObservation obs{Eigen::Vector2d(0.07, -0.03),
                               Eigen::Vector2d(0.4, -0.25), 0.0031};
    const TimedWorldPointReprojectionFactor timed(obs, 300.0);
    const WorldPointReprojectionFactor plain(obs.xy, 300.0);
    f.blocks[3][0] = obs.t_d_at_stamp;
    std::vector<RowMajorMatrix> J_timed(4), J_plain(3);
    const Eigen::Vector2d r_timed = Evaluate(timed, f.blocks, &J_timed);
    const std::vector<std::vector<double>> three(f.blocks.begin(),
                                                 f.blocks.begin() + 3);
    const Eigen::Vector2d r_plain = Evaluate(plain, three, &J_plain);
    EXPECT_EQ(r_timed, r_plain);
    for (size_t b = 0; b < 3; ++b) EXPECT_EQ(J_timed[b], J_plain[b]) << b;
  }
}

// A camera moving along a smooth simulated trajectory (constant body
// velocity, acceleration and angular rate): the frame's pose is placed at
// IMU time tau_k = t_cam + t_d_k, the sighting is the true projection at the
// real instant t_cam + t_true, and v_k the image velocity at tau_k by a
// central difference of the true projection (nothing of the factor's code).
// For any t_d, the sighting the factor compares with, recovered from its
// residual as xy_shifted = pi(pose_k, p_w) - r / sqrt_info, is the true
// projection at t_cam + t_true - (t_d - t_d_k) to second order in the shift;
// at t_d = t_true the residual vanishes to that order.
TEST(TimedWorldPointReprojectionFactor, ShiftedSightingIsTheProjectionThen) {
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int t = 0; t < 20; ++t) {
    const bool camera1 = t % 2 == 1;
    const VisualScene s = SampleVisualScene(
        rng, VisualGeometry::kRealistic,
        camera1 ? VisualTarget::kStereoOtherFrame
                : VisualTarget::kMonoOtherFrame,
        /*timed=*/false, 0.0);
    const Eigen::Isometry3d T_b_c =
        IsometryFromBlock(camera1 ? s.extrinsic1 : s.extrinsic0);
    const Eigen::Isometry3d T_w_b0 = IsometryFromBlock(s.pose_j);
    const Eigen::Vector3d p_w = SceneWorldPoint(s);
    // Up to 2 m/s, 3 m/s^2 and 1.5 rad/s (the aggressive preset's range).
    const Eigen::Vector3d v(2.0 * unit(rng), 2.0 * unit(rng), 2.0 * unit(rng));
    const Eigen::Vector3d a(3.0 * unit(rng), 3.0 * unit(rng), 3.0 * unit(rng));
    const Eigen::Vector3d w(1.5 * unit(rng), 1.5 * unit(rng), 1.5 * unit(rng));
    auto body = [&](double tau) {
      Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
      T.linear() = T_w_b0.linear() * Exp(w * tau);
      T.translation() = T_w_b0.translation() + v * tau + 0.5 * a * tau * tau;
      return T;
    };
    auto project = [&](double tau) {
      const Eigen::Vector3d p_c = (body(tau) * T_b_c).inverse() * p_w;
      return Eigen::Vector2d(p_c.head<2>() / p_c.z());
    };
    const double t_cam = 0.0;
    const double t_true = 0.006;   // the real offset [s]
    const double t_d_k = -0.002;   // the estimate that placed the pose [s]
    const double tau_k = t_cam + t_d_k;
    const double h = 1e-5;
    const Eigen::Vector2d v_k = (project(tau_k + h) - project(tau_k - h)) /
                                (2.0 * h);
    const TimedObservation obs{project(t_cam + t_true), v_k, t_d_k};
    const double sqrt_info = 300.0;
    const TimedWorldPointReprojectionFactor factor(obs, sqrt_info);
    const Eigen::Isometry3d T_k = body(tau_k);
    std::vector<std::vector<double>> blocks = {
        std::vector<double>(7), std::vector<double>(7),
        std::vector<double>(p_w.data(), p_w.data() + 3), {0.0}};
    const Block7 pose = BlockFromIsometry(T_k);
    const Block7 ext = BlockFromIsometry(T_b_c);
    blocks[0].assign(pose.data(), pose.data() + 7);
    blocks[1].assign(ext.data(), ext.data() + 7);
    const Eigen::Vector2d at_pose = project(tau_k);
    // The image acceleration at tau_k, for the second-order bound.
    const double h2 = 1e-3;
    const double acc = ((project(tau_k + h2) - 2.0 * at_pose +
                         project(tau_k - h2)) /
                        (h2 * h2))
                           .norm();
    for (const double t_d : {-0.010, -0.002, 0.0, 0.003, 0.006, 0.012}) {
      blocks[3][0] = t_d;
      const Eigen::Vector2d r = Evaluate(factor, blocks);
      const Eigen::Vector2d xy_shifted = at_pose - r / sqrt_info;
      const Eigen::Vector2d truth = project(t_cam + t_true - (t_d - t_d_k));
      // Taylor at tau_k: the sighting is pi + D1 v + acc D1^2 / 2 with
      // D1 = t_true - t_d_k, the truth pi + D2 v + acc D2^2 / 2 with
      // D2 = t_true - t_d, and the factor takes the first orders alike; what
      // is left is acc |D1^2 - D2^2| / 2 (20 % margin for the third order).
      const double d1 = t_true - t_d_k;
      const double d2 = t_true - t_d;
      const double bound = 0.6 * acc * std::abs(d1 * d1 - d2 * d2) + 1e-9;
      EXPECT_LT((xy_shifted - truth).norm(), bound)
          << "trial " << t << " t_d " << t_d << " |v_k| " << v_k.norm()
          << " first-order shift " << (v_k * (t_d - t_d_k)).norm();
      if (t_d == t_true) {
        // The residual vanishes to second order.
        EXPECT_LT(r.norm() / sqrt_info, 0.6 * acc * d1 * d1 + 1e-9);
      }
    }
  }
}

TEST(TimedWorldPointReprojectionFactor, PointBehindTheCameraIsFiniteAndInactive) {
  std::mt19937 rng(13);
  for (int t = 0; t < 20; ++t) {
    VisualScene s = SampleVisualScene(rng, VisualGeometry::kRealistic,
                                      VisualTarget::kMonoOtherFrame, true);
    const Eigen::Isometry3d T_w_c =
        TargetCameraPose(s, VisualTarget::kMonoOtherFrame) *
        Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX());
    SetTargetCameraPose(T_w_c, VisualTarget::kMonoOtherFrame, &s);
    FactorInstance f = MakeTimedWorldPointReprojection(s, false);
    std::vector<RowMajorMatrix> J(4);
    const Eigen::Vector2d r = Evaluate(*f.cost, f.blocks, &J);
    EXPECT_TRUE(r.allFinite());
    EXPECT_GT(r.norm(), 100.0);
    for (const auto& j : J) EXPECT_TRUE(j.isZero(0.0));
  }
}

TEST(TimedWorldPointReprojectionFactor, FirstEstimateJacobiansAreTakenThere) {
  // keep_point_fej: the residual at p_w, every Jacobian (t_d's included)
  // that of the plain timed factor at p_w_first.
  const FactorCase c = MakeTimedWorldPointReprojectionCase();
  std::mt19937 rng(17);
  for (int t = 0; t < 50; ++t) {
    const FactorInstance f = c.sample(rng);
    const TimedObservation obs{Eigen::Vector2d(0.05, -0.02),
                               Eigen::Vector2d(-0.3, 0.2), 0.001};
    const TimedWorldPointReprojectionFactor plain(obs, 300.0);
    std::vector<double> first = f.blocks[2];
    first[0] += 0.03;
    first[2] -= 0.05;
    const TimedWorldPointReprojectionFactor fej(obs, 300.0, first.data());
    std::vector<std::vector<double>> at_first = f.blocks;
    at_first[2] = first;
    std::vector<RowMajorMatrix> J_fej(4), J_first(4);
    const Eigen::Vector2d r_fej = Evaluate(fej, f.blocks, &J_fej);
    const Eigen::Vector2d r_plain = Evaluate(plain, f.blocks);
    Evaluate(plain, at_first, &J_first);
    EXPECT_EQ(r_fej, r_plain);
    for (size_t b = 0; b < 4; ++b) EXPECT_EQ(J_fej[b], J_first[b]) << b;
  }
}

}  // namespace
}  // namespace vio
