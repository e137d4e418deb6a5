// Marginalisation on a visual-inertial window built from real data: EuRoC
// MH_05_difficult's IMU preintegrated into the project's IMU factor between
// five keyframes 0.5 s apart (ground-truth states, perturbed), and three
// points seen from every keyframe. The IMU fixes roll and pitch through
// gravity; global position and yaw stay unobservable (the 4-DoF gauge of
// VIO), and the prior must not invent information along them.

#include <ceres/crs_matrix.h>
#include <ceres/loss_function.h>
#include <ceres/problem.h>
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "dataset/euroc_reader.h"
#include "dataset/trajectory_io.h"
#include "estimator/marginalization.h"
#include "factors/imu_factor.h"
#include "factors/pose_manifold.h"
#include "geometry/so3.h"
#include "preintegration/imu_preintegration.h"
#include "test/testing/pose_test_factors.h"

namespace vio {
namespace {

const std::string kDir =
    std::string(VIO_SHARED_DIR) + "/data/euroc_MH_05_imu_gt/mav0/";
constexpr double kGravity = 9.81;  // [m/s^2]
constexpr int kKeyframes = 5;
constexpr int kPoints = 3;
constexpr size_t kFirstState = 4000;  // 20 s into the flight
constexpr size_t kStride = 100;       // 0.5 s at 200 Hz

class MarginalizationImuTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    imu_ = new std::vector<ImuSample>(ReadEurocImu(kDir + "imu0/data.csv"));
    gt_ = new std::vector<StampedState>(
        ReadEurocGroundTruth(kDir + "state_groundtruth_estimate0/data.csv"));
  }
  static void TearDownTestSuite() {
    delete imu_;
    delete gt_;
  }

  void SetUp() override {
    ASSERT_GT(gt_->size(), kFirstState + kKeyframes * kStride);
    std::mt19937 rng(5);
    std::normal_distribution<double> n(0.0, 1.0);
    auto noise = [&](double sigma) -> Eigen::Vector3d {
      return Eigen::Vector3d(n(rng), n(rng), n(rng)) * sigma;
    };
    for (int k = 0; k < kKeyframes; ++k) {
      const StampedState& s = (*gt_)[kFirstState + k * kStride];
      const Eigen::Vector3d p = s.p_w_b + noise(0.05);
      const Eigen::Quaterniond q = s.q_w_b * ExpQuaternion(noise(0.01));
      const Eigen::Vector3d v = s.v_w + noise(0.05);
      const Eigen::Vector3d b_a = s.b_a + noise(0.01);
      const Eigen::Vector3d b_g = s.b_g + noise(0.001);
      poses_[k] = {p.x(), p.y(), p.z(), q.x(), q.y(), q.z(), q.w()};
      speed_biases_[k] = {v.x(),   v.y(),   v.z(),   b_a.x(), b_a.y(),
                          b_a.z(), b_g.x(), b_g.y(), b_g.z()};
      truth_.push_back(s);
    }
    for (int k = 0; k + 1 < kKeyframes; ++k) {
      const ImuPreintegration pre(
          truth_[k].t_ns, truth_[k + 1].t_ns, *imu_,
          Eigen::Vector3d(speed_biases_[k].data() + kSpeedBiasBa),
          Eigen::Vector3d(speed_biases_[k].data() + kSpeedBiasBg), ImuNoise(),
          PreintegrationOptions());
      costs_.push_back(std::make_unique<ImuFactor>(pre.result(), kGravity));
      blocks_.push_back({poses_[k].data(), speed_biases_[k].data(),
                         poses_[k + 1].data(), speed_biases_[k + 1].data()});
    }
    for (int l = 0; l < kPoints; ++l) {
      const Eigen::Vector3d p_w = truth_[0].p_w_b + noise(4.0);
      points_[l] = {p_w.x(), p_w.y(), p_w.z()};
      for (int k = 0; k < kKeyframes; ++k) {
        const Eigen::Matrix3d R_T =
            truth_[k].q_w_b.toRotationMatrix().transpose();
        costs_.push_back(std::make_unique<testing::PointTestFactor>(
            R_T * (p_w - truth_[k].p_w_b) + noise(0.02),
            50.0 * Eigen::Matrix3d::Identity()));
        blocks_.push_back({poses_[k].data(), points_[l].data()});
      }
    }
  }

  // Marginalises keyframe 0 (pose and speed-bias) and point 0.
  MarginalizationResult MarginaliseFirst() {
    MarginalizationProblem problem;
    for (auto& p : poses_)
      problem.parameter_blocks.push_back({p.data(), 7, &pm_});
    for (auto& s : speed_biases_)
      problem.parameter_blocks.push_back({s.data(), 9});
    for (auto& l : points_) problem.parameter_blocks.push_back({l.data(), 3});
    problem.marginalized = {poses_[0].data(), speed_biases_[0].data(),
                            points_[0].data()};
    for (size_t f = 0; f < costs_.size(); ++f) {
      bool touches = false;
      for (double* b : blocks_[f]) {
        for (const double* m : problem.marginalized) touches |= b == m;
      }
      if (touches) {
        problem.residual_blocks.push_back(
            {costs_[f].get(), huber_.get(), blocks_[f]});
      }
    }
    return Marginalize(problem);
  }

  // A global motion of the whole window as a tangent vector over the prior's
  // kept blocks: a translation t of the world, plus a small rotation by the
  // vector a [rad] of the world about its origin.
  Eigen::VectorXd GlobalMotion(const MarginalizationResult& r,
                               const Eigen::Vector3d& t,
                               const Eigen::Vector3d& a) const {
    Eigen::VectorXd d(r.jacobian.cols());
    int offset = 0;
    for (size_t b = 0; b < r.kept_blocks.size(); ++b) {
      const double* x = r.kept_parameter_blocks[b];
      const int size = r.kept_blocks[b].AmbientSize();
      if (size == 7) {  // p -> Exp(a) p + t;  R -> Exp(a) R = R Exp(R^T a)
        const Eigen::Map<const Eigen::Vector3d> p(x);
        const Eigen::Quaterniond q(Eigen::Map<const Eigen::Vector4d>(x + 3));
        d.segment<3>(offset) = t + a.cross(p);
        d.segment<3>(offset + 3) = q.toRotationMatrix().transpose() * a;
        offset += 6;
      } else if (size == 9) {  // v -> Exp(a) v; biases are body-frame
        d.segment<3>(offset) = a.cross(Eigen::Map<const Eigen::Vector3d>(x));
        d.segment<6>(offset + 3).setZero();
        offset += 9;
      } else {  // a point: l -> Exp(a) l + t
        d.segment<3>(offset) =
            t + a.cross(Eigen::Map<const Eigen::Vector3d>(x));
        offset += 3;
      }
    }
    return d;
  }

  // |J d|^2 / (lambda_max(H*) |d|^2): the prior's information along d,
  // relative to its largest.
  static double RelativeInformation(const MarginalizationResult& r,
                                    const Eigen::VectorXd& d) {
    const double lambda_max =
        Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(r.information)
            .eigenvalues()
            .maxCoeff();
    return (r.jacobian * d).squaredNorm() / (lambda_max * d.squaredNorm());
  }

  inline static std::vector<ImuSample>* imu_ = nullptr;
  inline static std::vector<StampedState>* gt_ = nullptr;
  std::vector<StampedState> truth_;
  std::vector<double> poses_[kKeyframes];
  std::vector<double> speed_biases_[kKeyframes];
  std::vector<double> points_[kPoints];
  std::vector<std::unique_ptr<ceres::CostFunction>> costs_;
  std::vector<std::vector<double*>> blocks_;
  std::shared_ptr<ceres::LossFunction> huber_ =
      std::make_shared<ceres::HuberLoss>(1.0);
  PoseManifold pm_;
};

// Along global translation and yaw the prior holds only the eigenvalue floor
// (1e-10 of its largest eigenvalue; measured: exactly that), while roll and
// pitch carry real information (measured 7.7e-4 and 1.5e-4 of the largest).
TEST_F(MarginalizationImuTest, PriorHasNoInformationAlongTheVioGauge) {
  const MarginalizationResult r = MarginaliseFirst();
  ASSERT_TRUE(r.ok()) << r.message;
  const double floor = MarginalizationOptions().prior_eigenvalue_floor;
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_LT(RelativeInformation(
                  r, GlobalMotion(r, Eigen::Vector3d::Unit(axis), zero)),
              2.0 * floor)
        << "translation along axis " << axis;
  }
  EXPECT_LT(
      RelativeInformation(r, GlobalMotion(r, zero, Eigen::Vector3d::UnitZ())),
      2.0 * floor)
      << "yaw";
  EXPECT_GT(
      RelativeInformation(r, GlobalMotion(r, zero, Eigen::Vector3d::UnitX())),
      1e-5)
      << "roll";
  EXPECT_GT(
      RelativeInformation(r, GlobalMotion(r, zero, Eigen::Vector3d::UnitY())),
      1e-5)
      << "pitch";
}

// With the project's IMU factor (and Huber-weighted points), the prior equals
// the Schur complement of Ceres' own linearisation, reduced with a full
// inverse (measured: 2.6e-13 of the largest entry apart).
TEST_F(MarginalizationImuTest, PriorEqualsDenseSchurComplementOfCeres) {
  const MarginalizationResult r = MarginaliseFirst();
  ASSERT_TRUE(r.ok()) << r.message;
  std::vector<double*> order = {poses_[0].data(), speed_biases_[0].data(),
                                points_[0].data()};
  const int m = 6 + 9 + 3;
  order.insert(order.end(), r.kept_parameter_blocks.begin(),
               r.kept_parameter_blocks.end());
  ceres::Problem::Options options;
  options.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(options);
  for (size_t f = 0; f < costs_.size(); ++f) {
    bool touches = false;
    for (double* b : blocks_[f])
      touches |= b == order[0] || b == order[1] || b == order[2];
    if (touches)
      problem.AddResidualBlock(costs_[f].get(), huber_.get(), blocks_[f]);
  }
  for (auto& p : poses_) {
    if (problem.HasParameterBlock(p.data()))
      problem.SetManifold(p.data(), &pm_);
  }
  ceres::Problem::EvaluateOptions eval;
  eval.parameter_blocks = order;
  std::vector<double> gradient;
  ceres::CRSMatrix crs;
  ASSERT_TRUE(problem.Evaluate(eval, nullptr, nullptr, &gradient, &crs));
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(crs.num_rows, crs.num_cols);
  for (int row = 0; row < crs.num_rows; ++row) {
    for (int k = crs.rows[row]; k < crs.rows[row + 1]; ++k) {
      J(row, crs.cols[k]) = crs.values[k];
    }
  }
  const Eigen::MatrixXd H = J.transpose() * J;
  const Eigen::VectorXd g =
      Eigen::Map<Eigen::VectorXd>(gradient.data(), gradient.size());
  const int k = static_cast<int>(H.rows()) - m;
  const Eigen::MatrixXd H_mm_inv = H.topLeftCorner(m, m).inverse();
  const Eigen::MatrixXd H_star =
      H.bottomRightCorner(k, k) -
      H.bottomLeftCorner(k, m) * H_mm_inv * H.topRightCorner(m, k);
  const Eigen::VectorXd g_star =
      g.tail(k) - H.bottomLeftCorner(k, m) * H_mm_inv * g.head(m);
  EXPECT_LT((r.information - H_star).cwiseAbs().maxCoeff(),
            1e-11 * H_star.cwiseAbs().maxCoeff());
  EXPECT_LT((r.gradient - g_star).cwiseAbs().maxCoeff(),
            1e-11 * g_star.cwiseAbs().maxCoeff());
}

}  // namespace
}  // namespace vio
