#include "test/testing/inverse_depth_window.h"

#include <ceres/crs_matrix.h>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <random>

#include "factors/reprojection_factor.h"
#include "geometry/so3.h"

namespace vio {
namespace testing {
namespace {

constexpr double kFocalPx = 460.0;
constexpr double kSigmaPx = 1.0;  // pixel noise of the observations

std::array<double, 7> Block(const Eigen::Isometry3d& T) {
  const Eigen::Quaterniond q(T.linear());
  return {T.translation().x(),
          T.translation().y(),
          T.translation().z(),
          q.x(),
          q.y(),
          q.z(),
          q.w()};
}

}  // namespace

InverseDepthWindow::InverseDepthWindow(bool tolerant_loss, unsigned seed)
    : huber_(std::make_unique<ceres::HuberLoss>(1.345)),
      tolerant_(std::make_unique<ceres::TolerantLoss>(0.5, 1.0)) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> n(0.0, 1.0);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto noise3 = [&](double sigma) -> Eigen::Vector3d {
    return Eigen::Vector3d(n(rng), n(rng), n(rng)) * sigma;
  };
  // Camera: x right, y down, z forward along the body's x axis.
  Eigen::Isometry3d T_b_c = Eigen::Isometry3d::Identity();
  T_b_c.linear() << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  T_b_c.translation() = Eigen::Vector3d(0.05, -0.02, 0.01);
  extrinsic_ = Block(T_b_c);
  std::array<Eigen::Isometry3d, kPoses> truth;
  for (int i = 0; i < kPoses; ++i) {
    truth[i] = Eigen::Isometry3d::Identity();
    truth[i].linear() =
        ExpQuaternion(Eigen::Vector3d(0.01 * i, -0.015 * i, 0.04 * i))
            .toRotationMatrix();
    truth[i].translation() = Eigen::Vector3d(0.25 * i, 0.08 * i * i, 0.03 * i);
  }
  // Landmarks in their anchor camera, 3-8 m ahead.
  std::array<Eigen::Vector3d, kLandmarks> p_w;
  for (int k = 0; k < kLandmarks; ++k) {
    anchor_[k] = k % 2;
    const double z = 3.0 + 2.5 * (u(rng) + 1.0);
    const Eigen::Vector3d p_c(0.5 * u(rng) * z, 0.4 * u(rng) * z, z);
    p_w[k] = truth[anchor_[k]] * T_b_c * p_c;
  }
  auto observe = [&](int i, int k) {
    const Eigen::Vector3d p_c = (truth[i] * T_b_c).inverse() * p_w[k];
    return Eigen::Vector2d(p_c.head<2>() / p_c.z() +
                           Eigen::Vector2d(n(rng), n(rng)) * kSigmaPx /
                               kFocalPx);
  };
  const double sqrt_info = kFocalPx / 1.5;
  for (int k = 0; k < kLandmarks; ++k) {
    const int a = anchor_[k];
    const Eigen::Vector2d xy_a = observe(a, k);
    for (int j = a + 1; j < kPoses; ++j) {
      residuals_.push_back(
          {std::make_shared<ReprojectionFactor>(xy_a, observe(j, k), sqrt_info),
           tolerant_loss && k % 5 == 4 ? tolerant_.get() : huber_.get(),
           {Pose(a), Pose(j), Extrinsic(), Rho(k)},
           a});
    }
    const double z_a = ((truth[a] * T_b_c).inverse() * p_w[k]).z();
    rho_[k] = (1.0 / z_a) * (1.0 + 0.1 * n(rng));
  }
  // The prior on poses 0 and 1: random SPD information about 1 cm and
  // 0.3 deg, centred near the truth.
  std::vector<PriorBlock> blocks;
  for (int i = 0; i < 2; ++i) {
    Eigen::Isometry3d T0 = truth[i];
    T0.translation() += noise3(0.005);
    const std::array<double, 7> x0 = Block(T0);
    blocks.push_back(
        {PriorBlockKind::kPose, std::vector<double>(x0.begin(), x0.end())});
  }
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(12, 12);
  for (int r = 0; r < 12; ++r) {
    for (int c = 0; c < 12; ++c) A(r, c) = 0.2 * u(rng);
  }
  Eigen::VectorXd sigma(12);
  sigma << 0.01, 0.01, 0.01, 0.005, 0.005, 0.005, 0.01, 0.01, 0.01, 0.005,
      0.005, 0.005;
  Eigen::MatrixXd info = sigma.cwiseInverse().asDiagonal();
  info = info * (Eigen::MatrixXd::Identity(12, 12) + A * A.transpose()) * info;
  const Eigen::MatrixXd J = info.llt().matrixU();
  Eigen::VectorXd r0(12);
  for (int r = 0; r < 12; ++r) r0[r] = 0.5 * n(rng);
  prior_ = std::make_unique<MarginalizationPrior>(blocks, J, r0);
  residuals_.push_back({std::shared_ptr<ceres::CostFunction>(
                            prior_.get(), [](ceres::CostFunction*) {}),
                        nullptr,
                        {Pose(0), Pose(1)},
                        -1});
  // Start away from the truth.
  for (int i = 0; i < kPoses; ++i) {
    Eigen::Isometry3d T = truth[i];
    T.translation() += noise3(0.03);
    T.linear() = T.linear() * ExpQuaternion(noise3(0.008)).toRotationMatrix();
    poses_[i] = Block(T);
  }
}

bool InverseDepthWindow::IsPose(const double* x) const {
  for (const auto& p : poses_) {
    if (p.data() == x) return true;
  }
  return x == extrinsic_.data();
}

std::vector<const InverseDepthWindow::Residual*> InverseDepthWindow::All()
    const {
  std::vector<const Residual*> all;
  for (const Residual& r : residuals_) all.push_back(&r);
  return all;
}

std::unique_ptr<ceres::Problem> InverseDepthWindow::CeresProblem(
    const std::vector<const Residual*>& residuals) {
  ceres::Problem::Options options;
  options.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  auto problem = std::make_unique<ceres::Problem>(options);
  for (const Residual* r : residuals) {
    problem->AddResidualBlock(
        r->cost.get(), const_cast<ceres::LossFunction*>(r->loss), r->blocks);
    for (double* b : r->blocks) {
      if (IsPose(b)) problem->SetManifold(b, &pose_manifold_);
    }
  }
  if (problem->HasParameterBlock(Extrinsic())) {
    problem->SetParameterBlockConstant(Extrinsic());
  }
  return problem;
}

void InverseDepthWindow::CeresLinearise(
    const std::vector<const Residual*>& residuals,
    const std::vector<double*>& order, Eigen::MatrixXd* H, Eigen::VectorXd* g) {
  const std::unique_ptr<ceres::Problem> problem = CeresProblem(residuals);
  ceres::Problem::EvaluateOptions eval;
  eval.parameter_blocks = order;
  std::vector<double> gradient;
  ceres::CRSMatrix crs;
  problem->Evaluate(eval, nullptr, nullptr, &gradient, &crs);
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(crs.num_rows, crs.num_cols);
  for (int row = 0; row < crs.num_rows; ++row) {
    for (int k = crs.rows[row]; k < crs.rows[row + 1]; ++k) {
      J(row, crs.cols[k]) = crs.values[k];
    }
  }
  *H = J.transpose() * J;
  *g = Eigen::Map<Eigen::VectorXd>(gradient.data(), gradient.size());
}

}  // namespace testing
}  // namespace vio
