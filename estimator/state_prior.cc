#include "estimator/state_prior.h"

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <vector>

#include "factors/pose_manifold.h"

namespace vio {

std::unique_ptr<MarginalizationPrior> MakeStatePrior(
    const double* pose, const double* speed_bias,
    const StatePriorOptions& sigmas, double velocity_sigma) {
  // Tangent order: [dp (3), dtheta (3)] of the pose, then v, b_a, b_g.
  Eigen::Matrix<double, 15, 15> J = Eigen::Matrix<double, 15, 15>::Zero();
  J.block<3, 3>(0, 0) = Eigen::Matrix3d::Identity() / sigmas.position_m;
  const Eigen::Quaterniond q_w_b(pose + 3);
  const Eigen::Vector3d u =
      q_w_b.normalized().conjugate() * Eigen::Vector3d::UnitZ();
  const Eigen::Matrix3d uu = u * u.transpose();
  const Eigen::Matrix3d info_rot =
      (Eigen::Matrix3d::Identity() - uu) / (sigmas.tilt_rad * sigmas.tilt_rad) +
      uu / (sigmas.yaw_rad * sigmas.yaw_rad);
  J.block<3, 3>(3, 3) = info_rot.llt().matrixU();
  J.block<3, 3>(6, 6) = Eigen::Matrix3d::Identity() / velocity_sigma;
  J.block<3, 3>(9, 9) = Eigen::Matrix3d::Identity() / sigmas.accel_bias;
  J.block<3, 3>(12, 12) = Eigen::Matrix3d::Identity() / sigmas.gyro_bias;
  std::vector<PriorBlock> blocks(2);
  blocks[0].kind = PriorBlockKind::kPose;
  blocks[0].x0.assign(pose, pose + 7);
  blocks[1].kind = PriorBlockKind::kEuclidean;
  blocks[1].x0.assign(speed_bias, speed_bias + 9);
  return std::make_unique<MarginalizationPrior>(blocks, Eigen::MatrixXd(J),
                                                Eigen::VectorXd::Zero(15));
}

std::unique_ptr<MarginalizationPrior> MakeExtrinsicPrior(
    const std::vector<const double*>& extrinsics,
    const StatePriorOptions& sigmas) {
  const int n = 6 * static_cast<int>(extrinsics.size());
  Eigen::VectorXd inverse_sigma(n);
  std::vector<PriorBlock> blocks(extrinsics.size());
  for (size_t c = 0; c < extrinsics.size(); ++c) {
    inverse_sigma.segment<3>(6 * c + kPoseTranslation)
        .setConstant(1.0 / sigmas.extrinsic_translation_m);
    inverse_sigma.segment<3>(6 * c + kPoseRotation)
        .setConstant(1.0 / sigmas.extrinsic_rotation_rad);
    blocks[c].kind = PriorBlockKind::kPose;
    blocks[c].x0.assign(extrinsics[c], extrinsics[c] + 7);
  }
  return std::make_unique<MarginalizationPrior>(
      blocks, Eigen::MatrixXd(inverse_sigma.asDiagonal()),
      Eigen::VectorXd::Zero(n));
}

std::unique_ptr<MarginalizationPrior> MakeBiasPrior(const double* speed_bias,
                                                    double accel_bias_sigma,
                                                    double gyro_bias_sigma) {
  Eigen::Matrix<double, 6, 9> J = Eigen::Matrix<double, 6, 9>::Zero();
  J.block<3, 3>(0, 3) = Eigen::Matrix3d::Identity() / accel_bias_sigma;
  J.block<3, 3>(3, 6) = Eigen::Matrix3d::Identity() / gyro_bias_sigma;
  std::vector<PriorBlock> blocks(1);
  blocks[0].kind = PriorBlockKind::kEuclidean;
  blocks[0].x0.assign(speed_bias, speed_bias + 9);
  return std::make_unique<MarginalizationPrior>(blocks, Eigen::MatrixXd(J),
                                                Eigen::VectorXd::Zero(6));
}

std::unique_ptr<MarginalizationPrior> MakeBiasLink(const double* speed_bias_i,
                                                   const double* speed_bias_j,
                                                   double accel_bias_sigma,
                                                   double gyro_bias_sigma) {
  Eigen::Matrix<double, 6, 1> w;
  w << Eigen::Vector3d::Constant(1.0 / accel_bias_sigma),
      Eigen::Vector3d::Constant(1.0 / gyro_bias_sigma);
  // Columns: [v, b_a, b_g] of i, then of j.
  Eigen::Matrix<double, 6, 18> J = Eigen::Matrix<double, 6, 18>::Zero();
  J.block<6, 6>(0, 3) = -Eigen::Matrix<double, 6, 6>(w.asDiagonal());
  J.block<6, 6>(0, 12) = w.asDiagonal();
  const Eigen::Map<const Eigen::Matrix<double, 6, 1>> b_i(speed_bias_i + 3);
  const Eigen::Map<const Eigen::Matrix<double, 6, 1>> b_j(speed_bias_j + 3);
  const Eigen::VectorXd r0 = w.asDiagonal() * (b_j - b_i);
  std::vector<PriorBlock> blocks(2);
  blocks[0].kind = PriorBlockKind::kEuclidean;
  blocks[0].x0.assign(speed_bias_i, speed_bias_i + 9);
  blocks[1].kind = PriorBlockKind::kEuclidean;
  blocks[1].x0.assign(speed_bias_j, speed_bias_j + 9);
  return std::make_unique<MarginalizationPrior>(blocks, Eigen::MatrixXd(J), r0);
}

}  // namespace vio
