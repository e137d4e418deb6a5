#include "estimator/state_prior.h"

#include <gtest/gtest.h>

#include "factors/pose_manifold.h"
#include "geometry/so3.h"

namespace vio {
namespace {

// The prior's information J^T J on the 15 tangent coordinates of
// [pose, speed-bias], with the rotation block stated about world axes.
TEST(StatePrior, InformationMatchesTheSigmasAboutWorldAxes) {
  const Eigen::Quaterniond q_w_b =
      ExpQuaternion(Eigen::Vector3d(0.4, -0.3, 1.2));
  double pose[7] = {1, 2, 3, q_w_b.x(), q_w_b.y(), q_w_b.z(), q_w_b.w()};
  double speed_bias[9] = {0.1, 0, 0, 0.01, 0.02, 0.03, 0.001, 0.002, 0.003};
  StatePriorOptions sigmas;
  const auto prior = MakeStatePrior(pose, speed_bias, sigmas, 0.3);
  const Eigen::MatrixXd info =
      prior->jacobian().transpose() * prior->jacobian();
  EXPECT_NEAR(info(0, 0), 1.0 / (sigmas.position_m * sigmas.position_m), 1e-6);
  EXPECT_NEAR(info(6, 6), 1.0 / (0.3 * 0.3), 1e-9);
  EXPECT_NEAR(info(9, 9), 1.0 / (sigmas.accel_bias * sigmas.accel_bias), 1e-9);
  EXPECT_NEAR(info(12, 12), 1.0 / (sigmas.gyro_bias * sigmas.gyro_bias), 1e-6);
  // A body-frame rotation dtheta turns the body by R dtheta in the world;
  // its yaw part is e_z . R dtheta. So u = R^T e_z carries 1 / sigma_yaw^2
  // and any direction perpendicular to it 1 / sigma_tilt^2.
  const Eigen::Matrix3d info_rot = info.block<3, 3>(3, 3);
  const Eigen::Vector3d u = q_w_b.conjugate() * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d w = u.unitOrthogonal();
  EXPECT_NEAR(u.dot(info_rot * u), 1.0 / (sigmas.yaw_rad * sigmas.yaw_rad),
              1e-3);
  EXPECT_NEAR(w.dot(info_rot * w), 1.0 / (sigmas.tilt_rad * sigmas.tilt_rad),
              1e-6);
  // At x0 the residual is zero; it evaluates without NaN.
  const double* params[2] = {pose, speed_bias};
  Eigen::VectorXd r(15);
  ASSERT_TRUE(prior->Evaluate(params, r.data(), nullptr));
  EXPECT_NEAR(r.norm(), 0.0, 1e-12);
}

}  // namespace
}  // namespace vio
