// The notes' frame tracker (frontend/direct_tracker.h) on real EuRoC images:
// aligning cam1 to cam0 with the stereo pair's depths recovers the
// calibrated T_c1_c0 (both solvers), the damping follows the notes' rule, and
// the hand-derived Jacobian rows of frontend/photometric_alignment.h match
// numeric differentiation and the photometric factor.

#include "frontend/direct_tracker.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "factors/photometric_factor.h"
#include "frontend/direct_keyframe.h"
#include "geometry/so3.h"
#include "testing/direct_sequence.h"

namespace vio {
namespace {

constexpr double kDeg = M_PI / 180.0;

double AngleDeg(const Eigen::Isometry3d& T) {
  return Log(Eigen::Matrix3d(T.linear())).norm() / kDeg;
}

// V1_01 (the vehicle stands still): the keyframe is cam0 of pair 0 with the
// pair's semi-dense depth at level 1; the targets are cam1 of pair 0 and of
// pair 40 (other image noise, same geometry).
class V101Stereo : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    seq_ =
        new testing::StereoSequence(testing::SharedData("euroc_V1_01_first5s"));
    const PinholeUndistorter u0(seq_->cam0), u1(seq_->cam1);
    const ImagePyramid left(u0.Undistort(testing::ReadGrey(seq_->left[0])),
                            u0.pinhole(), 5);
    const ImagePyramid right(u1.Undistort(testing::ReadGrey(seq_->right[0])),
                             u1.pinhole(), 5);
    keyframe_ = new DirectKeyframe(MakeDirectKeyframe(
        0, left,
        StereoInverseDepth(left.level(1), right.level(1), seq_->T_c1_c0(), 1,
                           StereoDepthOptions()),
        1));
    for (size_t frame : {size_t{0}, size_t{40}}) {
      targets_.push_back(std::make_unique<ImagePyramid>(
          u1.Undistort(testing::ReadGrey(seq_->right[frame])), u1.pinhole(),
          5));
    }
  }
  static void TearDownTestSuite() {
    delete seq_;
    delete keyframe_;
    targets_.clear();
  }

  // The calibrated T_c1_c0 moved by `scale` times 2 degrees and 2 cm.
  static AlignmentState PerturbedStart(double scale = 1.0) {
    Eigen::Isometry3d off = Eigen::Isometry3d::Identity();
    off.linear() =
        Exp(Eigen::Vector3d(2.0, -1.0, 1.0).normalized() * 2 * scale * kDeg);
    off.translation() =
        Eigen::Vector3d(1.0, -1.0, 1.0).normalized() * 0.02 * scale;
    AlignmentState s;
    s.T_t_h = seq_->T_c1_c0() * off;
    return s;
  }

  static testing::StereoSequence* seq_;
  static DirectKeyframe* keyframe_;
  static std::vector<std::unique_ptr<ImagePyramid>> targets_;
};

testing::StereoSequence* V101Stereo::seq_ = nullptr;
DirectKeyframe* V101Stereo::keyframe_ = nullptr;
std::vector<std::unique_ptr<ImagePyramid>> V101Stereo::targets_;

TEST_F(V101Stereo, AligningCam1ToCam0RecoversTheCalibratedExtrinsic) {
  ASSERT_GT(keyframe_->points[1].size(), 3000u);
  const AlignmentState start = PerturbedStart();
  const Eigen::Isometry3d E0 = seq_->T_c1_c0().inverse() * start.T_t_h;
  EXPECT_NEAR(AngleDeg(E0), 2.0, 1e-9);
  EXPECT_NEAR(E0.translation().norm(), 0.02, 0.002);
  for (size_t t = 0; t < targets_.size(); ++t) {
    Eigen::Isometry3d results[2];
    for (DirectSolver solver : {DirectSolver::kNotesLm, DirectSolver::kCeres}) {
      DirectTrackerOptions options;
      options.solver = solver;
      const TrackResult r =
          DirectTracker(options).Track(*keyframe_, *targets_[t], nullptr,
                                       Eigen::Isometry3d::Identity(), start);
      ASSERT_TRUE(r.ok) << r.failure;
      const Eigen::Isometry3d E = seq_->T_c1_c0().inverse() * r.state.T_t_h;
      std::printf(
          "cam1 of pair %d, %s solver: %.4f deg, %.2f mm from the "
          "calibration; a = %.3f, b = %.1f; %zu log rows\n",
          t == 0 ? 0 : 40, DirectSolverName(solver), AngleDeg(E),
          E.translation().norm() * 1e3, r.state.affine[0][0],
          r.state.affine[0][1], r.log.size());
      EXPECT_LT(AngleDeg(E), 0.2);
      EXPECT_LT(E.translation().norm(), 0.005);
      results[solver == DirectSolver::kCeres] = r.state.T_t_h;
    }
    // The two solvers minimise the same cost: they end together.
    const Eigen::Isometry3d D = results[0].inverse() * results[1];
    EXPECT_LT(AngleDeg(D), 0.01);
    EXPECT_LT(D.translation().norm(), 0.5e-3);
  }
}

// Algorithm 3: after an accepted solve lambda is halved, or set to 0 once
// <= 0.2; after a rejected one it is set to 0.2 from 0, else doubled; the
// error of the accepted states decreases.
TEST_F(V101Stereo, DampingFollowsTheNotesRule) {
  // From 6 degrees and 6 cm the coarse levels start outside the region
  // where Gauss-Newton steps are good, so solves are rejected and accepted
  // again at raised lambda; a tiny epsilon_1 keeps every level iterating.
  DirectTrackerOptions options;
  options.min_step = 1e-9;
  const TrackResult r = DirectTracker(options).Track(
      *keyframe_, *targets_[0], nullptr, Eigen::Isometry3d::Identity(),
      PerturbedStart(3.0));
  ASSERT_TRUE(r.ok);
  int rejected = 0, checked = 0;
  for (size_t i = 0; i + 1 < r.log.size(); ++i) {
    const TrackIteration& a = r.log[i];
    const TrackIteration& b = r.log[i + 1];
    if (b.level != a.level) continue;  // each level starts at lambda 0
    double expected;
    if (a.iteration == 0) {
      expected = 0.0;
    } else if (a.accepted) {
      expected = a.lambda <= 0.2 ? 0.0 : 0.5 * a.lambda;
    } else {
      expected = a.lambda == 0.0 ? 0.2 : 2.0 * a.lambda;
      ++rejected;
    }
    EXPECT_DOUBLE_EQ(b.lambda, expected) << "log row " << i + 1;
    ++checked;
  }
  EXPECT_GT(rejected, 0) << "the run never exercised a rejection";
  int halved = 0;  // accepted at lambda > 0.2: the halving branch
  for (const TrackIteration& it : r.log) {
    halved += it.accepted && it.iteration > 0 && it.lambda > 0.2;
  }
  EXPECT_GT(halved, 0) << "the run never exercised the halving";
  EXPECT_GT(checked, 20);
  // Accepted errors decrease within a level.
  double last = 0.0;
  int level = -1;
  for (const TrackIteration& it : r.log) {
    if (it.level != level) {
      level = it.level;
      last = it.error;
      continue;
    }
    if (it.accepted) {
      EXPECT_LT(it.error, last);
      last = it.error;
    }
  }
}

// The hand-derived rows (photometric_alignment.cc) against central
// differences through PhotometricAlignment::Plus and a perturbed inverse
// depth, on real points, into cam1 as the left target and into a "right"
// target 11 cm further (the stereo term's chain).
TEST_F(V101Stereo, AlignmentJacobianRowsMatchNumericDiff) {
  const int level = 1;
  std::vector<DepthPoint> points = keyframe_->points[level];
  Eigen::Isometry3d T_r_l = Eigen::Isometry3d::Identity();
  T_r_l.translation() = Eigen::Vector3d(-0.11, 0.002, 0.001);
  T_r_l.linear() = Exp(Eigen::Vector3d(0.01, -0.02, 0.005));
  const std::vector<AlignmentTarget> targets = {
      {&targets_[0]->level(level), Eigen::Isometry3d::Identity(), 1.0, 0},
      {&targets_[1]->level(level), T_r_l, 0.5, 1}};
  const PhotometricAlignment problem(points,
                                     keyframe_->image.level(level).camera,
                                     targets, DirectTrackerOptions());
  AlignmentState state = PerturbedStart();
  state.affine[0] = Eigen::Vector2d(-0.1, 3.0);
  state.affine[1] = Eigen::Vector2d(0.05, -2.0);
  constexpr double h = 1e-6;
  int checked = 0;
  double worst = 0.0;
  for (size_t m = 0; m < points.size(); m += 53) {
    for (size_t k = 0; k < targets.size(); ++k) {
      AlignmentResidual r;
      if (!problem.Residual(m, k, state, &r)) continue;
      Eigen::VectorXd J(problem.num_unknowns());
      J.setZero();
      J.head<6>() = r.d_f_d_pose.transpose();
      J.segment<2>(6 + 2 * k) = r.d_f_d_affine;
      Eigen::VectorXd numeric(J.size());
      bool ok = true;
      for (int i = 0; i < J.size(); ++i) {
        Eigen::VectorXd step = Eigen::VectorXd::Zero(J.size());
        step[i] = h;
        AlignmentResidual plus, minus;
        ok = ok && problem.Residual(m, k, problem.Plus(state, step), &plus) &&
             problem.Residual(m, k, problem.Plus(state, -step), &minus);
        numeric[i] = (plus.f - minus.f) / (2 * h);
      }
      // d f / d rho through a copy of the point with a moved inverse depth.
      const double rho = points[m].rho;
      AlignmentResidual plus, minus;
      points[m].rho = rho + h;
      ok = ok && problem.Residual(m, k, state, &plus);
      points[m].rho = rho - h;
      ok = ok && problem.Residual(m, k, state, &minus);
      points[m].rho = rho;
      if (!ok) continue;  // a step crossed the image border
      ++checked;
      const double scale = numeric.cwiseAbs().maxCoeff();
      const double error = (J - numeric).cwiseAbs().maxCoeff() / scale;
      const double rho_numeric = (plus.f - minus.f) / (2 * h);
      const double rho_error =
          std::abs(r.d_f_d_rho - rho_numeric) / std::max(scale, 1e-9);
      worst = std::max({worst, error, rho_error});
      EXPECT_LT(error, 2e-4) << "point " << m << " target " << k;
      EXPECT_LT(rho_error, 2e-4) << "point " << m << " target " << k;
    }
  }
  EXPECT_GT(checked, 100);
  std::printf("worst relative error of %d rows: %.2e\n", checked, worst);
}

// The tracker's residual and weight are the photometric factor's: pose_i =
// identity, pose_j = delta^-1, the target camera at T_k_t^-1.
TEST_F(V101Stereo, AlignmentResidualIsThePhotometricFactor) {
  const int level = 2;
  const std::vector<DepthPoint>& points = keyframe_->points[level];
  const std::vector<AlignmentTarget> targets = {
      {&targets_[0]->level(level), Eigen::Isometry3d::Identity(), 1.0, 0}};
  const DirectTrackerOptions options;
  const PhotometricAlignment problem(
      points, keyframe_->image.level(level).camera, targets, options);
  AlignmentState state = PerturbedStart();
  state.affine[0] = Eigen::Vector2d(-0.1, 3.0);
  const Eigen::Isometry3d T_h_t = state.T_t_h.inverse();
  Eigen::Matrix<double, 7, 1> pose_i, pose_j;
  pose_i << 0, 0, 0, 0, 0, 0, 1;
  pose_j << T_h_t.translation(), Eigen::Quaterniond(T_h_t.linear()).coeffs();
  const double ab_i[2] = {0.0, 0.0};
  const double ab_j[2] = {-0.1, 3.0};
  const Rigid identity{Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero()};
  int compared = 0;
  for (size_t m = 0; m < points.size(); m += 7) {
    AlignmentResidual r;
    if (!problem.Residual(m, 0, state, &r)) continue;
    const PhotometricFactor factor({points[m].uv, points[m].intensity,
                                    keyframe_->image.level(level).camera},
                                   targets[0].level->image,
                                   targets[0].level->camera, identity, identity,
                                   1.0);
    const double* params[] = {pose_i.data(), pose_j.data(), &points[m].rho,
                              ab_i, ab_j};
    double f = 0.0, d_f_d_rho = 0.0;
    ASSERT_TRUE(factor.InverseDepthDerivative(params, &f, &d_f_d_rho));
    EXPECT_NEAR(r.f, f, 1e-9);
    EXPECT_NEAR(r.d_f_d_rho, d_f_d_rho, 1e-9 * std::max(1.0, std::abs(f)));
    EXPECT_NEAR(r.weight,
                PhotometricWeight(options.sigma_intensity, d_f_d_rho,
                                  points[m].variance),
                1e-12);
    ++compared;
  }
  EXPECT_GT(compared, 300);
}

TEST(DirectTracker, KeyframeWithoutPointsFailsCleanly) {
  const std::vector<float> flat(64 * 48, 100.0f);
  cv::Mat image(48, 64, CV_32F, const_cast<float*>(flat.data()));
  const ImagePyramid pyramid(image, {50, 50, 31.5, 23.5}, 3);
  const DirectKeyframe kf = MakeDirectKeyframe(0, pyramid, {}, 0);
  DirectTrackerOptions options;
  options.coarsest_level = 2;
  options.finest_level = 0;
  const TrackResult r = DirectTracker(options).Track(
      kf, pyramid, nullptr, Eigen::Isometry3d::Identity(), AlignmentState());
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.failure, "the keyframe has no points at the finest level");
  options.coarsest_level = 5;
  EXPECT_FALSE(DirectTracker(options)
                   .Track(kf, pyramid, nullptr, Eigen::Isometry3d::Identity(),
                          AlignmentState())
                   .ok);
  options.min_residuals = 3;
  EXPECT_THROW(DirectTracker{options}, std::invalid_argument);
}

}  // namespace
}  // namespace vio
