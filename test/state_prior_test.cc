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

// One camera's extrinsic prior: information 1 / sigma^2 on [dt, dtheta], zero
// residual at the calibration, and a translation error of one sigma costs
// exactly one unit of residual.
TEST(StatePrior, ExtrinsicPriorWeighsTheCalibrationBySigma) {
  const Eigen::Quaterniond q_b_c =
      ExpQuaternion(Eigen::Vector3d(-1.2, 0.1, 1.5));
  double T_b_c[7] = {0.05,      -0.02,     0.01,     q_b_c.x(),
                     q_b_c.y(), q_b_c.z(), q_b_c.w()};
  StatePriorOptions sigmas;
  const auto prior = MakeExtrinsicPrior({T_b_c}, sigmas);
  const Eigen::MatrixXd info =
      prior->jacobian().transpose() * prior->jacobian();
  ASSERT_EQ(info.rows(), 6);
  const double t_info =
      1.0 / (sigmas.extrinsic_translation_m * sigmas.extrinsic_translation_m);
  const double r_info =
      1.0 / (sigmas.extrinsic_rotation_rad * sigmas.extrinsic_rotation_rad);
  EXPECT_NEAR(info(kPoseTranslation + 1, kPoseTranslation + 1), t_info, 1e-6);
  EXPECT_NEAR(info(kPoseRotation + 2, kPoseRotation + 2), r_info, 1e-6);
  EXPECT_NEAR(info(kPoseTranslation, kPoseRotation), 0.0, 1e-12);
  const double* params[1] = {T_b_c};
  Eigen::VectorXd r(6);
  ASSERT_TRUE(prior->Evaluate(params, r.data(), nullptr));
  EXPECT_NEAR(r.norm(), 0.0, 1e-12);
  T_b_c[0] += sigmas.extrinsic_translation_m;
  ASSERT_TRUE(prior->Evaluate(params, r.data(), nullptr));
  EXPECT_NEAR(r.norm(), 1.0, 1e-9);
}

// The bias link is the bias random walk alone: at any values of both blocks
// it is W (b_j - b_i), whatever the velocities.
TEST(BiasLink, IsTheWeightedBiasDifferenceAndIgnoresVelocity) {
  double sb_i[9] = {0.5, -0.2, 0.1, 0.01, 0.02, 0.03, 0.001, 0.002, 0.003};
  double sb_j[9] = {0.4, -0.1, 0.0, 0.02, 0.01, 0.04, 0.0015, 0.001, 0.0035};
  const double sigma_ba = 2e-3, sigma_bg = 1.5e-5;
  const auto link = MakeBiasLink(sb_i, sb_j, sigma_ba, sigma_bg);
  // Away from x0: other velocities and biases in both blocks.
  double x_i[9] = {3.0, 1.0, -1.0, 0.05, 0.0, 0.03, 0.0011, 0.002, 0.0};
  double x_j[9] = {-2.0, 0.0, 7.0, 0.04, 0.01, 0.02, 0.001, 0.0025, 0.003};
  const double* params[2] = {x_i, x_j};
  Eigen::Matrix<double, 6, 1> r;
  ASSERT_TRUE(link->Evaluate(params, r.data(), nullptr));
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(r[k], (x_j[3 + k] - x_i[3 + k]) / sigma_ba, 1e-9) << k;
    EXPECT_NEAR(r[3 + k], (x_j[6 + k] - x_i[6 + k]) / sigma_bg, 1e-6) << k;
  }
  // A bias prior holds one block's biases at x0, velocity free.
  const auto prior = MakeBiasPrior(sb_i, 0.2, 0.005);
  const double* one[1] = {x_i};
  ASSERT_TRUE(prior->Evaluate(one, r.data(), nullptr));
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(r[k], (x_i[3 + k] - sb_i[3 + k]) / 0.2, 1e-12) << k;
    EXPECT_NEAR(r[3 + k], (x_i[6 + k] - sb_i[6 + k]) / 0.005, 1e-12) << k;
  }
}

}  // namespace
}  // namespace vio
