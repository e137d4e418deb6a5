#ifndef VIO_TEST_TESTING_MARGINALIZATION_WINDOW_H_
#define VIO_TEST_TESTING_MARGINALIZATION_WINDOW_H_

// The test fixture shared by the marginalisation tests: a small window on
// real poses (EuRoC MH_05_difficult ground truth) with the analytic test
// factors of pose_test_factors.h, and Ceres' own linearisation of any subset
// of it, against which the marginalisation is compared.

#include <ceres/crs_matrix.h>
#include <ceres/loss_function.h>
#include <ceres/problem.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <exception>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "dataset/trajectory_io.h"
#include "estimator/marginalization.h"
#include "factors/pose_manifold.h"
#include "geometry/so3.h"
#include "test/testing/pose_test_factors.h"

namespace vio {
namespace testing {

constexpr int kNumPoses = 4;
constexpr int kNumPoints = 3;
constexpr int kFirstState = 4000;  // 20 s into MH_05, while flying
constexpr int kStateStride = 100;  // 0.5 s at 200 Hz

// A residual block of the test problem, owning its cost and loss.
struct Residual {
  std::shared_ptr<ceres::CostFunction> cost;
  std::shared_ptr<ceres::LossFunction> loss;
  std::vector<double*> blocks;
};

// A small window on real poses: 4 poses of MH_05_difficult's ground truth
// (0.5 s apart), their speeds (3, Euclidean) and 3 points (3, Euclidean),
// all perturbed away from the truth, with a pose prior on pose 0, relative
// pose factors, speed differences, pose-speed and pose-point factors (the
// latter with a Huber loss, some of them in its linear region).
class MarginalizationWindowTest : public ::testing::Test {
 protected:
  // The ground truth is read once for all tests (22k lines).
  static void SetUpTestSuite() {
    try {
      ground_truth_ = new std::vector<StampedState>(ReadEurocGroundTruth(
          std::string(VIO_SHARED_DIR) +
          "/data/euroc_MH_05_imu_gt/mav0/state_groundtruth_estimate0/"
          "data.csv"));
    } catch (const std::exception& e) {
      load_error_ = e.what();
    }
  }
  static void TearDownTestSuite() {
    delete ground_truth_;
    ground_truth_ = nullptr;
  }

  void SetUp() override {
    ASSERT_NE(ground_truth_, nullptr) << load_error_;
    const std::vector<StampedState>& gt = *ground_truth_;
    ASSERT_GT(gt.size(), kFirstState + kNumPoses * kStateStride);
    std::mt19937 rng(42);
    std::normal_distribution<double> n(0.0, 1.0);
    auto noise = [&](double sigma) -> Eigen::Vector3d {
      return Eigen::Vector3d(n(rng), n(rng), n(rng)) * sigma;
    };
    for (int i = 0; i < kNumPoses; ++i) {
      const StampedState& s = gt[kFirstState + i * kStateStride];
      truth_.push_back(s);
      const Eigen::Vector3d p = s.p_w_b + noise(0.05);
      const Eigen::Quaterniond q = s.q_w_b * ExpQuaternion(noise(0.02));
      poses_[i] = {p.x(), p.y(), p.z(), q.x(), q.y(), q.z(), q.w()};
      const Eigen::Vector3d v = s.v_w + noise(0.05);
      speeds_[i] = {v.x(), v.y(), v.z()};
    }
    for (int k = 0; k < kNumPoints; ++k) {
      const Eigen::Vector3d l_true = truth_[0].p_w_b + noise(3.0);
      points_true_.push_back(l_true);
      const Eigen::Vector3d l = l_true + noise(0.1);
      points_[k] = {l.x(), l.y(), l.z()};
    }
    BuildResiduals(noise);
  }

  template <typename Noise>
  void BuildResiduals(Noise& noise) {
    Matrix6d W_rel = Matrix6d::Zero();
    W_rel.diagonal() << 20, 20, 20, 100, 100, 100;
    W_rel(0, 4) = 15.0;  // some correlation between blocks' coordinates
    const Eigen::Vector3d t0 = truth_[0].p_w_b + noise(0.02);
    Add(std::make_shared<PosePriorTestFactor>(t0, truth_[0].q_w_b,
                                              10.0 * Matrix6d::Identity()),
        nullptr, {Pose(0)});
    for (int i = 0; i + 1 < kNumPoses; ++i) {
      const Eigen::Matrix3d R_i_T =
          truth_[i].q_w_b.toRotationMatrix().transpose();
      const Eigen::Vector3d t_ij =
          R_i_T * (truth_[i + 1].p_w_b - truth_[i].p_w_b) + noise(0.02);
      const Eigen::Quaterniond q_ij = truth_[i].q_w_b.conjugate() *
                                      truth_[i + 1].q_w_b *
                                      ExpQuaternion(noise(0.005));
      Add(std::make_shared<RelativePoseTestFactor>(t_ij, q_ij, W_rel), nullptr,
          {Pose(i), Pose(i + 1)});
      const Eigen::Vector3d dv = truth_[i + 1].v_w - truth_[i].v_w;
      Add(std::make_shared<DifferenceTestFactor>(
              dv + noise(0.02), 10.0 * Eigen::Matrix3d::Identity()),
          nullptr, {Speed(i), Speed(i + 1)});
    }
    for (int i = 0; i < kNumPoses; ++i) {
      const Eigen::Matrix3d R_T =
          truth_[i].q_w_b.toRotationMatrix().transpose();
      // Pose-speed coupling: v seen in the body frame, R^T (v - t).
      const Eigen::Vector3d z_v = R_T * (truth_[i].v_w - truth_[i].p_w_b);
      Add(std::make_shared<PointTestFactor>(z_v + noise(0.05),
                                            20.0 * Eigen::Matrix3d::Identity()),
          nullptr, {Pose(i), Speed(i)});
      for (int k = 0; k < kNumPoints; ++k) {
        const Eigen::Vector3d z = R_T * (points_true_[k] - truth_[i].p_w_b);
        Add(std::make_shared<PointTestFactor>(
                z + noise(0.05), 10.0 * Eigen::Matrix3d::Identity()),
            huber_, {Pose(i), Point(k)});
      }
    }
  }

  void Add(std::shared_ptr<ceres::CostFunction> cost,
           std::shared_ptr<ceres::LossFunction> loss,
           std::vector<double*> blocks) {
    residuals_.push_back({std::move(cost), std::move(loss), std::move(blocks)});
  }

  double* Pose(int i) { return poses_[i].data(); }
  double* Speed(int i) { return speeds_[i].data(); }
  double* Point(int k) { return points_[k].data(); }

  bool IsPose(const double* x) const {
    for (const auto& p : poses_) {
      if (p.data() == x) return true;
    }
    return false;
  }
  int SizeOf(const double* x) const { return IsPose(x) ? 7 : 3; }

  std::vector<MarginalizationParameterBlock> AllBlocks() {
    std::vector<MarginalizationParameterBlock> blocks;
    for (int i = 0; i < kNumPoses; ++i) {
      blocks.push_back({Pose(i), 7, &pose_manifold_, false});
    }
    for (int i = 0; i < kNumPoses; ++i) blocks.push_back({Speed(i), 3});
    for (int k = 0; k < kNumPoints; ++k) blocks.push_back({Point(k), 3});
    return blocks;
  }

  static bool Touches(const Residual& r, const std::vector<double*>& set) {
    for (double* b : r.blocks) {
      for (double* s : set) {
        if (b == s) return true;
      }
    }
    return false;
  }

  // The marginalisation input for the blocks in marg.
  MarginalizationProblem ProblemFor(const std::vector<double*>& marg) {
    MarginalizationProblem problem;
    problem.parameter_blocks = AllBlocks();
    for (const Residual& r : residuals_) {
      if (Touches(r, marg)) {
        problem.residual_blocks.push_back(
            {r.cost.get(), r.loss.get(), r.blocks});
      }
    }
    problem.marginalized.assign(marg.begin(), marg.end());
    return problem;
  }

  // Linearises residuals over the tangent space with Ceres itself
  // (ceres::Problem::Evaluate, loss applied) in the given block order:
  // returns H = J^T J and g = J^T r.
  void CeresLinearise(const std::vector<const Residual*>& residuals,
                      const std::vector<double*>& order, Eigen::MatrixXd* H,
                      Eigen::VectorXd* g) {
    ceres::Problem::Options options;
    options.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    ceres::Problem problem(options);
    for (const Residual* r : residuals) {
      problem.AddResidualBlock(r->cost.get(), r->loss.get(), r->blocks);
    }
    for (double* b : order) {
      if (!problem.HasParameterBlock(b))
        problem.AddParameterBlock(b, SizeOf(b));
      if (IsPose(b)) problem.SetManifold(b, &pose_manifold_);
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
    *H = J.transpose() * J;
    *g = Eigen::Map<Eigen::VectorXd>(gradient.data(), gradient.size());
  }

  // The Schur complement of the residual blocks touching marg, linearised by
  // Ceres and reduced with a full inverse: H* and the gradient g*.
  void DenseSchur(const std::vector<double*>& marg,
                  const std::vector<double*>& kept, Eigen::MatrixXd* H_star,
                  Eigen::VectorXd* g_star) {
    std::vector<double*> order = marg;
    order.insert(order.end(), kept.begin(), kept.end());
    Eigen::MatrixXd H;
    Eigen::VectorXd g;
    CeresLinearise(Select(marg, true), order, &H, &g);
    const int m = TangentSizeOf(marg, *this);
    const int k = static_cast<int>(H.rows()) - m;
    const Eigen::MatrixXd H_mm_inv = H.topLeftCorner(m, m).inverse();
    *H_star = H.bottomRightCorner(k, k) -
              H.bottomLeftCorner(k, m) * H_mm_inv * H.topRightCorner(m, k);
    *g_star = g.tail(k) - H.bottomLeftCorner(k, m) * H_mm_inv * g.head(m);
  }

  std::vector<const Residual*> Select(const std::vector<double*>& marg,
                                      bool touching) {
    std::vector<const Residual*> out;
    for (const Residual& r : residuals_) {
      if (Touches(r, marg) == touching) out.push_back(&r);
    }
    return out;
  }

  static int TangentSizeOf(const std::vector<double*>& blocks,
                           const MarginalizationWindowTest& t) {
    int n = 0;
    for (double* b : blocks) n += t.IsPose(b) ? 6 : 3;
    return n;
  }

  inline static std::vector<StampedState>* ground_truth_ = nullptr;
  inline static std::string load_error_;
  std::vector<StampedState> truth_;
  std::vector<Eigen::Vector3d> points_true_;
  std::vector<double> poses_[kNumPoses];
  std::vector<double> speeds_[kNumPoses];
  std::vector<double> points_[kNumPoints];
  std::vector<Residual> residuals_;
  std::shared_ptr<ceres::LossFunction> huber_ =
      std::make_shared<ceres::HuberLoss>(1.0);
  PoseManifold pose_manifold_;
};

inline double MaxAbs(const Eigen::MatrixXd& m) {
  return m.cwiseAbs().maxCoeff();
}

// A non-owning view of a cost function, for FactorInstance (which owns).
class Borrowed final : public ceres::CostFunction {
 public:
  explicit Borrowed(const ceres::CostFunction* f) : f_(f) {
    set_num_residuals(f->num_residuals());
    *mutable_parameter_block_sizes() = f->parameter_block_sizes();
  }
  bool Evaluate(double const* const* p, double* r, double** j) const override {
    return f_->Evaluate(p, r, j);
  }

 private:
  const ceres::CostFunction* f_;
};

}  // namespace testing
}  // namespace vio

#endif  // VIO_TEST_TESTING_MARGINALIZATION_WINDOW_H_
