// The marginalisation's floored square root on the world points' case
// (estimator/null_space_floor.h, FloorBlockDirections): a frame leaves with
// one mono sighting of each of several world points that stay. Checked here
// with the real WorldPointReprojectionFactor (first-estimate Jacobians, a
// Huber loss, the extrinsic estimated): that the ray from the leaving
// camera's centre to the point's first estimate is an exact null vector of
// H* (the claim the floor rests on), that the prior is floored block by
// block and equals the eigen path's floor of the same H*, and that with a
// null space the blocks do not hold (the gauge free) another path is taken
// and the prior is still the eigen path's.

#include <ceres/loss_function.h>
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <array>
#include <vector>

#include "estimator/marginalization.h"
#include "factors/pose_manifold.h"
#include "factors/world_point_factor.h"
#include "test/testing/eigen_path_floor.h"
#include "test/testing/pose_test_factors.h"

namespace vio {
namespace {

using testing::Matrix6d;
using testing::PosePriorTestFactor;
using testing::RelativePoseTestFactor;

constexpr double kFloor = 1e-10;  // MarginalizationOptions' prior floor
constexpr int kPoints = 6;

Eigen::Quaterniond Rotation(double angle, const Eigen::Vector3d& axis) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle, axis.normalized()));
}

void SetPose(const Eigen::Vector3d& t, const Eigen::Quaterniond& q,
             std::array<double, 7>* pose) {
  for (int i = 0; i < 3; ++i) (*pose)[i] = t[i];
  (*pose)[3] = q.x();
  (*pose)[4] = q.y();
  (*pose)[5] = q.z();
  (*pose)[6] = q.w();
}

Eigen::Isometry3d Isometry(const std::array<double, 7>& pose) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::Quaterniond(pose.data() + 3).toRotationMatrix();
  T.translation() = Eigen::Vector3d(pose.data());
  return T;
}

// Pose 0 leaves with one sighting of each point (its camera's extrinsic
// T_b_c kept, with a prior of its own); poses 1 and 2 stay, linked to it by
// relative-pose factors; pose 0 has a prior (the gauge) unless `gauge_free`.
// The sightings are the projections at the points' values plus a few
// pixels, some beyond the Huber threshold; the factors' first estimates are
// a few centimetres off the values.
class WorldPointFloor : public ::testing::Test {
 protected:
  void SetUp() override {
    SetPose({0.0, 0.0, 0.0}, Rotation(0.1, {0.3, 1.0, 0.2}), &poses_[0]);
    SetPose({0.6, 0.1, 0.05}, Rotation(0.15, {0.2, 1.0, 0.1}), &poses_[1]);
    SetPose({1.1, 0.3, 0.1}, Rotation(0.2, {0.1, 1.0, 0.3}), &poses_[2]);
    SetPose({0.05, -0.02, 0.01}, Rotation(1.5, {0.1, 0.05, 1.0}), &T_b_c_);
    const Eigen::Isometry3d T_w_c = Isometry(poses_[0]) * Isometry(T_b_c_);
    for (int i = 0; i < kPoints; ++i) {
      const Eigen::Vector3d p_c(0.4 * (i - 2.5), 0.2 * (i % 3) - 0.2,
                                3.0 + 0.5 * i);
      const Eigen::Vector3d p_w = T_w_c * p_c;
      const Eigen::Vector3d first = p_w + Eigen::Vector3d(0.02, -0.03, 0.04);
      for (int j = 0; j < 3; ++j) {
        points_[i][j] = p_w[j];
        first_[i][j] = first[j];
      }
      const Eigen::Vector2d xy =
          p_c.head<2>() / p_c.z() + Eigen::Vector2d(0.004, -0.003) * (i % 3);
      sightings_.push_back(std::make_unique<WorldPointReprojectionFactor>(
          xy, 460.0, first_[i].data()));
    }
    Matrix6d W = Matrix6d::Identity() * 100.0;
    prior_ = std::make_unique<PosePriorTestFactor>(
        Eigen::Vector3d(0.01, 0.0, 0.0), Rotation(0.1, {0.3, 1.0, 0.2}), W);
    weak_prior_ = std::make_unique<PosePriorTestFactor>(
        Eigen::Vector3d(0.01, 0.0, 0.0), Rotation(0.1, {0.3, 1.0, 0.2}),
        W * 1e-6);
    extrinsic_prior_ = std::make_unique<PosePriorTestFactor>(
        Eigen::Vector3d(0.05, -0.02, 0.01), Rotation(1.5, {0.1, 0.05, 1.0}),
        W * 10.0);
    for (int i = 0; i < 2; ++i) {
      const Eigen::Isometry3d T_ij =
          Isometry(poses_[i]).inverse() * Isometry(poses_[i + 1]);
      links_.push_back(std::make_unique<RelativePoseTestFactor>(
          T_ij.translation() + Eigen::Vector3d(0.01, 0.0, -0.01),
          Eigen::Quaterniond(T_ij.linear()), W * 3.0));
    }
  }

  // gauge_free: pose 0 without its prior; weak_gauge: with a prior 1e-6 as
  // strong (its directions below the floor but not zero).
  MarginalizationProblem Problem(bool gauge_free, bool weak_gauge = false) {
    MarginalizationProblem m;
    for (auto& pose : poses_)
      m.parameter_blocks.push_back({pose.data(), 7, &manifold_});
    m.parameter_blocks.push_back({T_b_c_.data(), 7, &manifold_});
    for (auto& p : points_) m.parameter_blocks.push_back({p.data(), 3});
    if (weak_gauge) {
      m.residual_blocks.push_back(
          {weak_prior_.get(), nullptr, {poses_[0].data()}});
    } else if (!gauge_free) {
      m.residual_blocks.push_back({prior_.get(), nullptr, {poses_[0].data()}});
    }
    m.residual_blocks.push_back(
        {extrinsic_prior_.get(), nullptr, {T_b_c_.data()}});
    for (int i = 0; i < 2; ++i) {
      m.residual_blocks.push_back(
          {links_[i].get(), nullptr, {poses_[i].data(), poses_[i + 1].data()}});
    }
    for (int i = 0; i < kPoints; ++i) {
      m.residual_blocks.push_back(
          {sightings_[i].get(),
           &huber_,
           {poses_[0].data(), T_b_c_.data(), points_[i].data()}});
    }
    m.marginalized = {poses_[0].data()};
    return m;
  }

  // The kept blocks' tangent offset of point i in H*.
  int PointOffset(const MarginalizationResult& result, int i) const {
    int offset = 0;
    for (size_t b = 0; b < result.kept_parameter_blocks.size(); ++b) {
      if (result.kept_parameter_blocks[b] == points_[i].data()) return offset;
      offset += result.kept_blocks[b].TangentSize();
    }
    return -1;
  }

  PoseManifold manifold_;
  ceres::HuberLoss huber_{1.345};
  std::array<std::array<double, 7>, 3> poses_{};
  std::array<double, 7> T_b_c_{};
  std::array<std::array<double, 3>, kPoints> points_{};
  std::array<std::array<double, 3>, kPoints> first_{};
  std::vector<std::unique_ptr<WorldPointReprojectionFactor>> sightings_;
  std::unique_ptr<PosePriorTestFactor> prior_, weak_prior_, extrinsic_prior_;
  std::vector<std::unique_ptr<RelativePoseTestFactor>> links_;
};

TEST_F(WorldPointFloor, TheRayFromTheLeavingCameraIsANullVectorOfHStar) {
  const MarginalizationResult result = Marginalize(Problem(false));
  ASSERT_TRUE(result.ok()) << result.message;
  const Eigen::MatrixXd& H = result.information;
  const double lambda_max =
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(H, Eigen::EigenvaluesOnly)
          .eigenvalues()
          .maxCoeff();
  const Eigen::Vector3d c_w =
      (Isometry(poses_[0]) * Isometry(T_b_c_)).translation();
  int beyond_huber = 0;
  for (int i = 0; i < kPoints; ++i) {
    const int offset = PointOffset(result, i);
    ASSERT_GE(offset, 0);
    // Along the ray to the first estimate (where the Jacobians are taken):
    // nothing, to rounding.
    Eigen::VectorXd v = Eigen::VectorXd::Zero(H.rows());
    v.segment<3>(offset) =
        (Eigen::Vector3d(first_[i].data()) - c_w).normalized();
    EXPECT_LT((H * v).norm(), 1e-14 * lambda_max) << i;
    // Along the ray to the current value, 3 cm away: not nothing (the
    // first estimates are what makes the ray above exact).
    v.segment<3>(offset) =
        (Eigen::Vector3d(points_[i].data()) - c_w).normalized();
    EXPECT_GT((H * v).norm(), 1e-9 * lambda_max) << i;
    std::array<const double*, 3> params = {poses_[0].data(), T_b_c_.data(),
                                           points_[i].data()};
    Eigen::Vector2d r;
    ASSERT_TRUE(sightings_[i]->Evaluate(params.data(), r.data(), nullptr));
    beyond_huber += r.squaredNorm() > 1.345 * 1.345 ? 1 : 0;
  }
  EXPECT_GT(beyond_huber, 0);  // the loss's scaling is exercised
}

TEST_F(WorldPointFloor, PriorIsFlooredBlockByBlockAsTheEigenPathWould) {
  const MarginalizationResult result = Marginalize(Problem(false));
  ASSERT_TRUE(result.ok()) << result.message;
  EXPECT_EQ(result.square_root, PriorSquareRoot::kBlockFloor);
  EXPECT_EQ(result.num_floored_eigenvalues, kPoints);
  int eigen_floored = 0;
  const Eigen::MatrixXd expected =
      testing::EigenPathFloor(result.information, kFloor, &eigen_floored);
  EXPECT_EQ(eigen_floored, kPoints);
  const double scale = expected.cwiseAbs().maxCoeff();
  const Eigen::MatrixXd& J = result.jacobian;
  EXPECT_LT((J.transpose() * J - expected).cwiseAbs().maxCoeff(),
            1e-13 * scale);
  EXPECT_EQ(result.floored_information.rows(), J.cols());
  EXPECT_LT((result.floored_information - expected).cwiseAbs().maxCoeff(),
            1e-13 * scale);
  // J^T r0 = -b* (the gradient) still.
  EXPECT_LT((J.transpose() * result.residual0 - result.gradient)
                .cwiseAbs()
                .maxCoeff(),
            1e-10 * result.gradient.cwiseAbs().maxCoeff());
}

TEST_F(WorldPointFloor, GaugeFreeNullSpaceTakesAnotherPathToTheSameFloor) {
  const MarginalizationResult result = Marginalize(Problem(true));
  ASSERT_TRUE(result.ok()) << result.message;
  EXPECT_NE(result.square_root, PriorSquareRoot::kBlockFloor);
  EXPECT_NE(result.square_root, PriorSquareRoot::kCholesky);
  int eigen_floored = 0;
  const Eigen::MatrixXd expected =
      testing::EigenPathFloor(result.information, kFloor, &eigen_floored);
  EXPECT_EQ(eigen_floored, kPoints + 6);  // the rays and the gauge
  EXPECT_EQ(result.num_floored_eigenvalues, kPoints + 6);
  const Eigen::MatrixXd& J = result.jacobian;
  EXPECT_LT((J.transpose() * J - expected).cwiseAbs().maxCoeff(),
            1e-12 * expected.cwiseAbs().maxCoeff());
}

// The gauge held by a prior 1e-6 as strong: six eigenvalues of H* below the
// floor, not zero, across all blocks. H_f of the block floor keeps them and
// has a Cholesky factor, but its pivots fail the test H* must pass to be
// used unfloored: another path floors all twelve, as the eigen path does.
TEST_F(WorldPointFloor, WeakGaugeBelowTheFloorIsNotLeftUnfloored) {
  const MarginalizationResult result = Marginalize(Problem(false, true));
  ASSERT_TRUE(result.ok()) << result.message;
  EXPECT_NE(result.square_root, PriorSquareRoot::kBlockFloor);
  int eigen_floored = 0;
  const Eigen::MatrixXd expected =
      testing::EigenPathFloor(result.information, kFloor, &eigen_floored);
  EXPECT_EQ(eigen_floored, kPoints + 6);
  EXPECT_EQ(result.num_floored_eigenvalues, kPoints + 6);
  const Eigen::MatrixXd& J = result.jacobian;
  EXPECT_LT((J.transpose() * J - expected).cwiseAbs().maxCoeff(),
            1e-12 * expected.cwiseAbs().maxCoeff());
}

}  // namespace
}  // namespace vio
