// The "marginalization_prior" case: random realistic priors over a window
// remainder (two poses, two speed-biases, three inverse depths), evaluated
// away from their linearisation point.

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <cmath>
#include <memory>
#include <utility>

#include "factors/check/factor_cases.h"
#include "factors/marginalization_prior.h"
#include "factors/pose_manifold.h"
#include "geometry/so3.h"

namespace vio {
namespace {

constexpr int kNumPoses = 2;
constexpr int kNumSpeedBias = 2;
constexpr int kNumInverseDepths = 3;
constexpr int kSpeedBiasSize = 9;

// Standard deviations of a typical window prior, per tangent coordinate of a
// block: they set the scale of the random information matrix.
constexpr double kSigmaPosition = 0.05;      // [m]
constexpr double kSigmaRotation = 0.01;      // [rad]
constexpr double kSigmaVelocity = 0.05;      // [m/s]
constexpr double kSigmaAccBias = 0.02;       // [m/s^2]
constexpr double kSigmaGyroBias = 0.002;     // [rad/s]
constexpr double kSigmaInverseDepth = 0.05;  // [1/m]

Eigen::Vector3d RandomVector(std::mt19937& rng, double sigma) {
  std::normal_distribution<double> n(0.0, sigma);
  return Eigen::Vector3d(n(rng), n(rng), n(rng));
}

std::vector<double> RandomPoseX0(std::mt19937& rng) {
  std::uniform_real_distribution<double> angle(0.0, M_PI - 1e-3);
  const Eigen::Vector3d axis = RandomVector(rng, 1.0).normalized();
  const Eigen::Vector3d t = RandomVector(rng, 5.0);  // [m]
  const Eigen::Quaterniond q = ExpQuaternion(angle(rng) * axis);
  return {t.x(), t.y(), t.z(), q.x(), q.y(), q.z(), q.w()};
}

std::vector<double> RandomSpeedBiasX0(std::mt19937& rng) {
  std::vector<double> x(kSpeedBiasSize);
  Eigen::Map<Eigen::Matrix<double, 9, 1>> m(x.data());
  m << RandomVector(rng, 1.0), RandomVector(rng, 0.1), RandomVector(rng, 0.01);
  return x;
}

// The per-coordinate standard deviations of all blocks, in tangent order.
Eigen::VectorXd TangentSigmas() {
  std::vector<double> s;
  for (int i = 0; i < kNumPoses; ++i) {
    for (int k = 0; k < 3; ++k) s.push_back(kSigmaPosition);
    for (int k = 0; k < 3; ++k) s.push_back(kSigmaRotation);
  }
  for (int i = 0; i < kNumSpeedBias; ++i) {
    for (double sigma : {kSigmaVelocity, kSigmaAccBias, kSigmaGyroBias}) {
      for (int k = 0; k < 3; ++k) s.push_back(sigma);
    }
  }
  for (int i = 0; i < kNumInverseDepths; ++i) s.push_back(kSigmaInverseDepth);
  return Eigen::Map<Eigen::VectorXd>(s.data(), static_cast<int>(s.size()));
}

// Random SPD information H = D (A^T A / n + 0.1 I) D with D = diag(1/sigma),
// correlated across blocks, and J = its upper Cholesky factor (J^T J = H).
Eigen::MatrixXd RandomSqrtInformation(std::mt19937& rng) {
  const Eigen::VectorXd sigma = TangentSigmas();
  const int n = static_cast<int>(sigma.size());
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::MatrixXd A(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) A(i, j) = normal(rng);
  }
  const Eigen::MatrixXd C =
      A.transpose() * A / n + 0.1 * Eigen::MatrixXd::Identity(n, n);
  const Eigen::VectorXd d = sigma.cwiseInverse();
  const Eigen::MatrixXd H = d.asDiagonal() * C * d.asDiagonal();
  return H.llt().matrixU();
}

// x = x0 (+) delta with |delta| from 1e-8 to a few sigma-sized steps.
std::vector<double> Perturbed(std::mt19937& rng, const std::vector<double>& x0,
                              PriorBlockKind kind, double scale) {
  std::vector<double> x(x0.size());
  if (kind == PriorBlockKind::kPose) {
    Eigen::Matrix<double, 6, 1> delta;
    delta << RandomVector(rng, 0.1 * scale), RandomVector(rng, 0.1 * scale);
    PoseManifold().Plus(x0.data(), delta.data(), x.data());
  } else {
    std::normal_distribution<double> n(0.0, 0.05 * scale);
    for (size_t i = 0; i < x0.size(); ++i) x[i] = x0[i] + n(rng);
  }
  return x;
}

FactorInstance SampleMarginalizationPrior(std::mt19937& rng) {
  std::vector<PriorBlock> blocks;
  FactorInstance f;
  for (int i = 0; i < kNumPoses; ++i) {
    blocks.push_back({PriorBlockKind::kPose, RandomPoseX0(rng)});
    f.block_names.push_back("pose_" + std::to_string(i));
  }
  for (int i = 0; i < kNumSpeedBias; ++i) {
    blocks.push_back({PriorBlockKind::kEuclidean, RandomSpeedBiasX0(rng)});
    f.block_names.push_back("speed_bias_" + std::to_string(i));
  }
  std::uniform_real_distribution<double> inverse_depth(0.05, 2.0);  // [1/m]
  for (int i = 0; i < kNumInverseDepths; ++i) {
    blocks.push_back({PriorBlockKind::kEuclidean, {inverse_depth(rng)}});
    f.block_names.push_back("inv_depth_" + std::to_string(i));
  }
  // Log-uniform distance from x0: from 1e-8 (rotation near identity, where
  // Jr^-1 takes its series branch) to about 0.5 rad and 0.5 m.
  std::uniform_real_distribution<double> log_scale(std::log(1e-7),
                                                   std::log(3.0));
  const double scale = std::exp(log_scale(rng));
  for (const PriorBlock& block : blocks) {
    f.blocks.push_back(Perturbed(rng, block.x0, block.kind, scale));
    f.manifolds.push_back(block.kind == PriorBlockKind::kPose
                              ? std::make_shared<PoseManifold>()
                              : nullptr);
  }
  const Eigen::MatrixXd J = RandomSqrtInformation(rng);
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::VectorXd r0(J.rows());
  for (int i = 0; i < r0.size(); ++i) r0[i] = normal(rng);
  f.cost = std::make_unique<MarginalizationPrior>(std::move(blocks), J, r0);
  return f;
}

}  // namespace

FactorCase MakeMarginalizationPriorCase() {
  FactorCase c;
  c.name = "marginalization_prior";
  c.description =
      "r0 + J (x (-) x0) over 2 poses, 2 speed-biases, 3 inverse depths";
  c.tolerance = 1e-6;
  c.sample = SampleMarginalizationPrior;
  return c;
}

}  // namespace vio
