#include "eval/nees.h"

#include <gtest/gtest.h>

#include "geometry/so3.h"

namespace vio {
namespace {

using Matrix6d = Eigen::Matrix<double, 6, 6>;

TEST(PoseNees, IsTheWhitenedSquaredErrorOnOurTangent) {
  const StampedPose truth{0, Eigen::Vector3d(1, 2, 3),
                          ExpQuaternion(Eigen::Vector3d(0.1, 0.2, 0.3))};
  StampedPose estimate = truth;
  estimate.p_w_b += Eigen::Vector3d(0.02, 0.0, -0.01);
  const Eigen::Vector3d dtheta(0.0, 0.003, 0.0);
  estimate.q_w_b = truth.q_w_b * ExpQuaternion(dtheta);
  Eigen::Matrix<double, 6, 1> sigma;
  sigma << 0.01, 0.02, 0.01, 0.001, 0.002, 0.003;
  const Matrix6d covariance = sigma.cwiseAbs2().asDiagonal();
  const PoseNees n = ComputePoseNees(estimate, truth, covariance);
  EXPECT_NEAR(n.position, 4.0 + 1.0, 1e-9);
  EXPECT_NEAR(n.rotation, 1.5 * 1.5, 1e-9);
  EXPECT_NEAR(n.pose, 5.0 + 2.25, 1e-9);
  // Yaw: the error along u = R^T e_z over u^T P u.
  const Eigen::Vector3d u =
      estimate.q_w_b.conjugate() * Eigen::Vector3d::UnitZ();
  const double var = u.dot(covariance.bottomRightCorner<3, 3>() * u);
  EXPECT_NEAR(n.yaw, std::pow(u.dot(dtheta), 2) / var, 1e-9);
}

TEST(GaugeTransform, AlignsPositionAndYawButNotTilt) {
  const StampedPose truth{0, Eigen::Vector3d(4, -1, 0.7),
                          ExpQuaternion(Eigen::Vector3d(0.2, -1.4, 0.6))};
  // The estimate's frame: the world turned by 1.1 rad about z and shifted,
  // and the estimate's attitude off by a small tilt.
  const Eigen::Quaterniond turn(
      Eigen::AngleAxisd(1.1, Eigen::Vector3d::UnitZ()));
  const Eigen::Quaterniond tilt(
      Eigen::AngleAxisd(0.01, Eigen::Vector3d::UnitX()));
  const StampedPose estimate{0, Eigen::Vector3d(0, 0, 0),
                             tilt * turn * truth.q_w_b};
  const StampedPose moved = Transform(GaugeTransform(estimate, truth), truth);
  EXPECT_LT((moved.p_w_b - estimate.p_w_b).norm(), 1e-12);
  const Eigen::Vector3d error = Log(moved.q_w_b.conjugate() * estimate.q_w_b);
  const Eigen::Vector3d u = moved.q_w_b.conjugate() * Eigen::Vector3d::UnitZ();
  EXPECT_LT(std::abs(u.dot(error)), 1e-10);  // no yaw left
  EXPECT_NEAR(error.norm(), 0.01, 1e-4);     // the tilt stays
}

}  // namespace
}  // namespace vio
