#include "estimator/marginalization.h"

#include <ceres/crs_matrix.h>
#include <ceres/loss_function.h>
#include <ceres/manifold.h>
#include <ceres/problem.h>
#include <ceres/sized_cost_function.h>
#include <ceres/solver.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "dataset/trajectory_io.h"
#include "factors/check/jacobian_check.h"
#include "factors/pose_manifold.h"
#include "geometry/so3.h"
#include "test/testing/pose_test_factors.h"

namespace vio {
namespace {

using testing::DifferenceTestFactor;
using testing::Matrix6d;
using testing::PointTestFactor;
using testing::PosePriorTestFactor;
using testing::RelativePoseTestFactor;

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
class MarginalizationTest : public ::testing::Test {
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
                           const MarginalizationTest& t) {
    int n = 0;
    for (double* b : blocks) n += t.IsPose(b) ? 6 : 3;
    return n;
  }

  static std::vector<StampedState>* ground_truth_;
  static std::string load_error_;
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

std::vector<StampedState>* MarginalizationTest::ground_truth_ = nullptr;
std::string MarginalizationTest::load_error_;

double MaxAbs(const Eigen::MatrixXd& m) { return m.cwiseAbs().maxCoeff(); }

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

TEST_F(MarginalizationTest, TestFactorJacobiansMatchNumericDiff) {
  for (const Residual& r : residuals_) {
    FactorInstance f;
    f.cost = std::make_unique<Borrowed>(r.cost.get());
    for (double* b : r.blocks) {
      f.blocks.emplace_back(b, b + SizeOf(b));
      f.manifolds.push_back(IsPose(b) ? std::make_shared<PoseManifold>()
                                      : nullptr);
    }
    std::vector<BlockJacobianError> errors;
    ASSERT_TRUE(CompareJacobians(f, {}, &errors));
    for (const auto& e : errors) EXPECT_LT(e.max_rel_error, 1e-6) << e.block;
  }
}

// The prior's information J^T J and gradient J^T r0 equal the Schur
// complement of the linearised problem, which Ceres linearises here (with the
// Huber loss applied by Ceres' own corrector) and the test reduces densely
// with a full inverse.
TEST_F(MarginalizationTest, PriorEqualsDenseSchurComplement) {
  const std::vector<double*> marg = {Pose(0), Speed(0), Point(0)};
  const MarginalizationResult result = Marginalize(ProblemFor(marg));
  ASSERT_EQ(result.status, MarginalizationStatus::kOk) << result.message;
  // These residual blocks alone hold only relative information on the kept
  // blocks (the gauge is in the pose-0 prior, which leaves): H* has 6 zero
  // eigenvalues, which the floor raises to 1e-10 of the largest.
  EXPECT_EQ(result.num_floored_eigenvalues, 6);

  Eigen::MatrixXd H_star;
  Eigen::VectorXd g_star;
  DenseSchur(marg, result.kept_parameter_blocks, &H_star, &g_star);

  const double h_scale = MaxAbs(H_star), g_scale = g_star.cwiseAbs().maxCoeff();
  EXPECT_LT(MaxAbs(result.information - H_star), 1e-10 * h_scale);
  EXPECT_LT(MaxAbs(result.gradient - g_star), 1e-10 * g_scale);
  const Eigen::MatrixXd& J = result.jacobian;
  EXPECT_LT(MaxAbs(J.transpose() * J - H_star), 1e-9 * h_scale);
  EXPECT_LT(MaxAbs(J.transpose() * result.residual0 - g_star), 1e-10 * g_scale);

  // The Huber loss is exercised: some point residuals lie beyond c = 1.
  int robust = 0;
  for (const Residual* r : Select(marg, true)) {
    if (r->loss == nullptr) continue;
    std::vector<const double*> p(r->blocks.begin(), r->blocks.end());
    Eigen::VectorXd res(r->cost->num_residuals());
    ASSERT_TRUE(r->cost->Evaluate(p.data(), res.data(), nullptr));
    robust += res.squaredNorm() > 1.0 ? 1 : 0;
  }
  EXPECT_GT(robust, 0);

  // The prior itself, linearised by Ceres at x = x0, carries the same.
  const std::unique_ptr<MarginalizationPrior> prior = result.MakePrior();
  Residual prior_residual{std::shared_ptr<ceres::CostFunction>(
                              prior.get(), [](ceres::CostFunction*) {}),
                          nullptr, result.kept_parameter_blocks};
  Eigen::MatrixXd H_prior;
  Eigen::VectorXd g_prior;
  CeresLinearise({&prior_residual}, result.kept_parameter_blocks, &H_prior,
                 &g_prior);
  EXPECT_LT(MaxAbs(H_prior - H_star), 1e-9 * h_scale);
  EXPECT_LT(MaxAbs(g_prior - g_star), 1e-10 * g_scale);
}

// One Gauss-Newton step of the whole problem, restricted to the kept blocks,
// equals the step of the reduced problem: the prior plus the residual blocks
// that did not touch the marginalised blocks.
TEST_F(MarginalizationTest, GaussNewtonStepWithPriorEqualsFullStep) {
  const std::vector<double*> marg = {Pose(0), Speed(0), Point(0)};
  const MarginalizationResult result = Marginalize(ProblemFor(marg));
  ASSERT_TRUE(result.ok()) << result.message;

  std::vector<double*> rest_order = result.kept_parameter_blocks;
  for (const auto& block : AllBlocks()) {
    bool listed = false;
    for (double* b : rest_order) listed = listed || b == block.values;
    for (double* b : marg) listed = listed || b == block.values;
    if (!listed) rest_order.push_back(block.values);
  }
  std::vector<double*> full_order = marg;
  full_order.insert(full_order.end(), rest_order.begin(), rest_order.end());

  Eigen::MatrixXd H_full;
  Eigen::VectorXd g_full;
  std::vector<const Residual*> all;
  for (const Residual& r : residuals_) all.push_back(&r);
  CeresLinearise(all, full_order, &H_full, &g_full);
  const Eigen::VectorXd dx_full = H_full.ldlt().solve(-g_full);

  const std::unique_ptr<MarginalizationPrior> prior = result.MakePrior();
  std::vector<const Residual*> reduced = Select(marg, false);
  Residual prior_residual{std::shared_ptr<ceres::CostFunction>(
                              prior.get(), [](ceres::CostFunction*) {}),
                          nullptr, result.kept_parameter_blocks};
  reduced.push_back(&prior_residual);
  Eigen::MatrixXd H_reduced;
  Eigen::VectorXd g_reduced;
  CeresLinearise(reduced, rest_order, &H_reduced, &g_reduced);
  const Eigen::VectorXd dx_reduced = H_reduced.ldlt().solve(-g_reduced);

  const int m = TangentSizeOf(marg, *this);
  const Eigen::VectorXd dx_kept = dx_full.tail(dx_full.size() - m);
  ASSERT_EQ(dx_kept.size(), dx_reduced.size());
  EXPECT_GT(dx_kept.norm(), 1e-3);  // the step is not trivially zero
  // Both sides are dense LDLT solves of a stiff system (weights from 10 to
  // 100, Huber-scaled rows); measured: 2.8e-9 relative.
  EXPECT_LT((dx_kept - dx_reduced).cwiseAbs().maxCoeff(),
            1e-8 * dx_kept.cwiseAbs().maxCoeff());
}

// Marginalising pose 0 and then pose 1 (re-marginalising the first prior)
// leaves the same information as marginalising both at once.
TEST_F(MarginalizationTest, RemarginalisingAPriorEqualsOneStep) {
  const std::vector<double*> first = {Pose(0), Speed(0), Point(0)};
  const MarginalizationResult step1 = Marginalize(ProblemFor(first));
  ASSERT_TRUE(step1.ok()) << step1.message;
  const std::unique_ptr<MarginalizationPrior> prior1 = step1.MakePrior();

  // Step 2 lists the first prior's kept blocks (as the estimator would) and
  // the window blocks the prior does not cover; the blocks of step 1 are gone.
  const std::vector<double*> second = {Pose(1), Speed(1)};
  const std::vector<double*> gone = first;
  MarginalizationProblem problem2;
  problem2.parameter_blocks = KeptParameterBlocks(step1, &pose_manifold_);
  for (const auto& p : AllBlocks()) {
    bool listed = false;
    for (const auto& q : problem2.parameter_blocks) {
      listed = listed || q.values == p.values;
    }
    for (double* g : gone) listed = listed || g == p.values;
    if (!listed) problem2.parameter_blocks.push_back(p);
  }
  for (const Residual& r : residuals_) {
    if (Touches(r, second) && !Touches(r, gone)) {
      problem2.residual_blocks.push_back(
          {r.cost.get(), r.loss.get(), r.blocks});
    }
  }
  problem2.residual_blocks.push_back(PriorResidualBlock(step1, prior1.get()));
  problem2.marginalized.assign(second.begin(), second.end());
  const MarginalizationResult step2 = Marginalize(problem2);
  ASSERT_TRUE(step2.ok()) << step2.message;

  std::vector<double*> both = first;
  both.insert(both.end(), second.begin(), second.end());
  const MarginalizationResult once = Marginalize(ProblemFor(both));
  ASSERT_TRUE(once.ok()) << once.message;

  // Compare block by block (the two results may order the kept blocks
  // differently).
  auto offsets = [this](const MarginalizationResult& r) {
    std::map<const double*, int> o;
    int offset = 0;
    for (double* b : r.kept_parameter_blocks) {
      o[b] = offset;
      offset += IsPose(b) ? 6 : 3;
    }
    return o;
  };
  const auto o2 = offsets(step2), o1 = offsets(once);
  ASSERT_EQ(o2.size(), o1.size());
  const double scale = MaxAbs(once.information);
  for (const auto& [a, ia] : o1) {
    ASSERT_EQ(o2.count(a), 1u);
    EXPECT_LT((step2.gradient.segment(o2.at(a), SizeOf(a) == 7 ? 6 : 3) -
               once.gradient.segment(ia, SizeOf(a) == 7 ? 6 : 3))
                  .cwiseAbs()
                  .maxCoeff(),
              1e-9 * once.gradient.cwiseAbs().maxCoeff());
    for (const auto& [b, ib] : o1) {
      const int na = IsPose(a) ? 6 : 3, nb = IsPose(b) ? 6 : 3;
      EXPECT_LT(MaxAbs(step2.information.block(o2.at(a), o2.at(b), na, nb) -
                       once.information.block(ia, ib, na, nb)),
                1e-9 * scale);
    }
  }
}

// A block held constant (say, a fixed extrinsic) gets no columns and is not
// kept: the result is the Schur complement with that block fixed.
TEST_F(MarginalizationTest, ConstantBlockIsNeitherColumnNorKept) {
  const std::vector<double*> marg = {Pose(0), Speed(0), Point(0)};
  MarginalizationProblem problem = ProblemFor(marg);
  for (auto& p : problem.parameter_blocks) {
    if (p.values == Point(1)) p.constant = true;
  }
  const MarginalizationResult result = Marginalize(problem);
  ASSERT_TRUE(result.ok()) << result.message;
  for (double* b : result.kept_parameter_blocks) EXPECT_NE(b, Point(1));
  Eigen::MatrixXd H_star;
  Eigen::VectorXd g_star;
  // Ceres holds the blocks missing from the evaluation order constant.
  DenseSchur(marg, result.kept_parameter_blocks, &H_star, &g_star);
  EXPECT_LT(MaxAbs(result.information - H_star), 1e-10 * MaxAbs(H_star));
  EXPECT_LT((result.gradient - g_star).cwiseAbs().maxCoeff(),
            1e-10 * g_star.cwiseAbs().maxCoeff());
}

// Returns a NaN residual, or fails, as a broken factor might.
class BrokenTestFactor final : public ceres::SizedCostFunction<1, 3> {
 public:
  explicit BrokenTestFactor(bool fail) : fail_(fail) {}
  bool Evaluate(double const* const*, double* residuals,
                double** jacobians) const override {
    residuals[0] = std::numeric_limits<double>::quiet_NaN();
    if (jacobians != nullptr && jacobians[0] != nullptr) {
      for (int i = 0; i < 3; ++i) jacobians[0][i] = 1.0;
    }
    return !fail_;
  }

 private:
  bool fail_;
};

bool AllFinite(const MarginalizationResult& r) {
  return r.jacobian.allFinite() && r.residual0.allFinite() &&
         r.information.allFinite() && r.gradient.allFinite();
}

TEST_F(MarginalizationTest, BrokenResidualBlocksAreSkippedAndCounted) {
  const std::vector<double*> marg = {Pose(0), Speed(0), Point(0)};
  const MarginalizationResult clean = Marginalize(ProblemFor(marg));
  MarginalizationProblem problem = ProblemFor(marg);
  const BrokenTestFactor nan_factor(false), failing_factor(true);
  problem.residual_blocks.push_back({&nan_factor, nullptr, {Point(0)}});
  problem.residual_blocks.push_back({&failing_factor, nullptr, {Speed(0)}});
  const MarginalizationResult result = Marginalize(problem);
  EXPECT_EQ(result.status, MarginalizationStatus::kDegenerate);
  EXPECT_EQ(result.num_skipped_residual_blocks, 2);
  EXPECT_EQ(result.num_residual_blocks_used, clean.num_residual_blocks_used);
  ASSERT_TRUE(AllFinite(result));
  EXPECT_LT(MaxAbs(result.information - clean.information),
            1e-12 * MaxAbs(clean.information));
}

// A point seen along one direction only (a rank-one observation) leaves
// H_mm rank deficient; it then carries no information to the pose, so the
// prior is exactly the pose factors' own information.
TEST_F(MarginalizationTest, RankDeficientMarginalBlockGivesStatusAndNoNaN) {
  Eigen::Matrix<double, 1, 3> e_x(10.0, 0.0, 0.0);
  const PointTestFactor one_direction(Eigen::Vector3d(1.0, 2.0, 3.0), e_x);
  const Residual& pose_prior = residuals_[0];  // touches pose 0 only
  const Residual& relative01 = residuals_[1];  // pose 0 - pose 1
  MarginalizationProblem problem;
  problem.parameter_blocks = AllBlocks();
  problem.residual_blocks = {
      {&one_direction, nullptr, {Pose(0), Point(0)}},
      {pose_prior.cost.get(), nullptr, pose_prior.blocks},
      {relative01.cost.get(), nullptr, relative01.blocks}};
  // Speed 0 is listed for marginalisation but no residual touches it.
  problem.marginalized = {Point(0), Speed(0)};
  const MarginalizationResult result = Marginalize(problem);
  EXPECT_EQ(result.status, MarginalizationStatus::kDegenerate);
  EXPECT_EQ(result.marginalized_rank_deficiency, 2 + 3);
  ASSERT_TRUE(AllFinite(result));

  Eigen::MatrixXd H;
  Eigen::VectorXd g;
  CeresLinearise({&pose_prior, &relative01}, result.kept_parameter_blocks, &H,
                 &g);
  EXPECT_LT(MaxAbs(result.information - H), 1e-9 * MaxAbs(H));
  EXPECT_LT((result.gradient - g).cwiseAbs().maxCoeff(),
            1e-9 * g.cwiseAbs().maxCoeff());
}

TEST_F(MarginalizationTest, NonFiniteParameterFailsWithMessage) {
  const std::vector<double*> marg = {Pose(0), Speed(0), Point(0)};
  Speed(1)[2] = std::numeric_limits<double>::quiet_NaN();
  const MarginalizationResult result = Marginalize(ProblemFor(marg));
  EXPECT_EQ(result.status, MarginalizationStatus::kFailed);
  EXPECT_NE(result.message.find("non-finite"), std::string::npos)
      << result.message;
  EXPECT_EQ(result.jacobian.size(), 0);
}

TEST_F(MarginalizationTest, NoUsableResidualFails) {
  const BrokenTestFactor nan_factor(false);
  MarginalizationProblem problem;
  problem.parameter_blocks = AllBlocks();
  problem.residual_blocks = {{&nan_factor, nullptr, {Point(0)}},
                             {&nan_factor, nullptr, {Point(1)}}};
  problem.marginalized = {Point(0)};
  const MarginalizationResult result = Marginalize(problem);
  EXPECT_EQ(result.status, MarginalizationStatus::kFailed);
  EXPECT_EQ(result.num_skipped_residual_blocks, 2);
}

TEST_F(MarginalizationTest, ResidualOnUnlistedBlockFails) {
  MarginalizationProblem problem = ProblemFor({Pose(0)});
  double unlisted[3] = {0.0, 0.0, 0.0};
  const BrokenTestFactor factor(false);
  problem.residual_blocks.push_back({&factor, nullptr, {unlisted}});
  const MarginalizationResult result = Marginalize(problem);
  EXPECT_EQ(result.status, MarginalizationStatus::kFailed);
  EXPECT_NE(result.message.find("unlisted"), std::string::npos);
}

TEST_F(MarginalizationTest, KeptBlockWithForeignManifoldFails) {
  MarginalizationProblem problem = ProblemFor({Pose(0)});
  const ceres::SubsetManifold fix_x(3, {0});
  for (auto& p : problem.parameter_blocks) {
    if (p.values == Speed(0)) p.manifold = &fix_x;
  }
  const MarginalizationResult result = Marginalize(problem);
  EXPECT_EQ(result.status, MarginalizationStatus::kFailed);
  EXPECT_NE(result.message.find("parameter block 4 is kept"), std::string::npos)
      << result.message;
}

// On a linear problem the prior is exact: Ceres solving the window with the
// prior in place of the leaving block reaches the full problem's solution on
// the kept blocks.
TEST(Marginalization, CeresSolveWithPriorMatchesFullSolveOnLinearChain) {
  constexpr int kBlocks = 5;
  std::mt19937 rng(3);
  std::normal_distribution<double> n(0.0, 1.0);
  std::vector<std::vector<double>> x(kBlocks, std::vector<double>(3, 0.0));
  std::vector<double> origin = {0.0, 0.0, 0.0};
  std::vector<std::unique_ptr<DifferenceTestFactor>> factors;
  std::vector<std::vector<double*>> blocks;
  for (int i = 0; i < kBlocks; ++i) {
    Eigen::Matrix3d W = Eigen::Matrix3d::Identity() * (5.0 + i);
    W(0, 1) = 1.0;
    double* from = i == 0 ? origin.data() : x[i - 1].data();
    factors.push_back(std::make_unique<DifferenceTestFactor>(
        Eigen::Vector3d(1.0 + n(rng), n(rng), n(rng)), W));
    blocks.push_back({from, x[i].data()});
  }
  // A second chain edge 0 -> 2 so that block 0 couples two kept blocks.
  factors.push_back(std::make_unique<DifferenceTestFactor>(
      Eigen::Vector3d(2.0, 0.5, -0.5), 3.0 * Eigen::Matrix3d::Identity()));
  blocks.push_back({x[0].data(), x[2].data()});

  MarginalizationProblem problem;
  problem.parameter_blocks.push_back({origin.data(), 3, nullptr, true});
  for (auto& b : x) problem.parameter_blocks.push_back({b.data(), 3});
  for (size_t f = 0; f < factors.size(); ++f) {
    const bool touches_0 =
        blocks[f][0] == x[0].data() || blocks[f][1] == x[0].data();
    if (touches_0)
      problem.residual_blocks.push_back({factors[f].get(), nullptr, blocks[f]});
  }
  problem.marginalized = {x[0].data()};
  const MarginalizationResult result = Marginalize(problem);
  ASSERT_EQ(result.status, MarginalizationStatus::kOk) << result.message;

  auto solve = [&](bool with_prior) {
    std::vector<std::vector<double>> saved = x;
    ceres::Problem::Options options;
    options.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    ceres::Problem ceres_problem(options);
    for (size_t f = 0; f < factors.size(); ++f) {
      const bool touches_0 =
          blocks[f][0] == x[0].data() || blocks[f][1] == x[0].data();
      if (!with_prior || !touches_0) {
        ceres_problem.AddResidualBlock(factors[f].get(), nullptr, blocks[f]);
      }
    }
    std::unique_ptr<MarginalizationPrior> prior = result.MakePrior();
    if (with_prior) {
      ceres_problem.AddResidualBlock(prior.get(), nullptr,
                                     result.kept_parameter_blocks);
    }
    if (ceres_problem.HasParameterBlock(origin.data())) {
      ceres_problem.SetParameterBlockConstant(origin.data());
    }
    ceres::Solver::Options solver;
    solver.max_num_iterations = 10;
    // A huge trust region makes LM's first step the Gauss-Newton step, which
    // solves a linear problem exactly.
    solver.initial_trust_region_radius = 1e16;
    solver.function_tolerance = 1e-16;
    solver.gradient_tolerance = 1e-16;
    solver.parameter_tolerance = 1e-16;
    ceres::Solver::Summary summary;
    ceres::Solve(solver, &ceres_problem, &summary);
    std::vector<std::vector<double>> solution = x;
    x = saved;
    return solution;
  };
  const auto full = solve(false);
  const auto reduced = solve(true);
  for (int i = 1; i < kBlocks; ++i) {
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(full[i][k], reduced[i][k], 1e-11) << "block " << i;
    }
  }
  EXPECT_GT(std::abs(full[kBlocks - 1][0]), 1.0);  // the solve moved x
}

}  // namespace
}  // namespace vio
