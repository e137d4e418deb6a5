// Direct stereo odometry (frontend/direct_odometry.h) on real images in
// motion: the first 2 s of euroc_MH_01_moving_6s (hand-held, fast and
// rotational) against the ground truth, per frame (frame to keyframe) and as
// the trajectory's ATE; the notes' variance weight against the unweighted
// alignment; and what it does with bad input.

#include "frontend/direct_odometry.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <vector>

#include "dataset/trajectory_io.h"
#include "eval/alignment.h"
#include "eval/association.h"
#include "eval/metrics.h"
#include "geometry/so3.h"
#include "testing/direct_sequence.h"

namespace vio {
namespace {

constexpr size_t kFrames = 40;  // 2 s at 20 Hz

struct RunStats {
  double mean_rot_deg = 0.0, mean_trans_mm = 0.0;  // frame to keyframe
  double max_rot_deg = 0.0, max_trans_mm = 0.0;
  double ate_m = 0.0;  // RMSE of the body positions after SE(3) alignment
  int tracked = 0;
  DirectOdometrySummary summary;
};

class MH01Motion : public ::testing::Test {
 public:
  static void SetUpTestSuite() {
    const std::string mav0 = testing::SharedData("euroc_MH_01_moving_6s");
    seq_ = new testing::StereoSequence(mav0);
    gt_ = new Trajectory(ReadTum(mav0 + "/ground_truth.tum"));
    for (size_t i = 0; i < kFrames; ++i) {
      left_.push_back(testing::ReadGrey(seq_->left[i]));
      right_.push_back(testing::ReadGrey(seq_->right[i]));
    }
  }
  static void TearDownTestSuite() {
    delete seq_;
    delete gt_;
    left_.clear();
    right_.clear();
  }

  static RunStats Run(const DirectOdometryOptions& options) {
    DirectOdometry odometry(seq_->cam0, seq_->cam1, options);
    const Eigen::Isometry3d T_b_c =
        testing::ToIsometry(seq_->cam0.q_b_c, seq_->cam0.t_b_c);
    Eigen::Isometry3d T_w_kf_gt = Eigen::Isometry3d::Identity();
    RunStats s;
    Trajectory estimate, truth;
    for (size_t i = 0; i < kFrames; ++i) {
      const int64_t t_ns = seq_->left[i].t_ns;
      const DirectFrame f = odometry.Process(t_ns, left_[i], right_[i]);
      const Eigen::Isometry3d T_w_c_gt =
          testing::GroundTruthCamera(*gt_, seq_->cam0, t_ns);
      if (f.tracked) {
        // The tracked T_c_kf against the ground truth's.
        const Eigen::Isometry3d E =
            (T_w_c_gt.inverse() * T_w_kf_gt).inverse() * f.track.state.T_t_h;
        const double rot = Log(Eigen::Matrix3d(E.linear())).norm() / M_PI * 180;
        const double trans = E.translation().norm() * 1e3;
        s.mean_rot_deg += rot;
        s.mean_trans_mm += trans;
        s.max_rot_deg = std::max(s.max_rot_deg, rot);
        s.max_trans_mm = std::max(s.max_trans_mm, trans);
        ++s.tracked;
      }
      if (f.keyframe) T_w_kf_gt = T_w_c_gt;
      const Eigen::Isometry3d T_w_b = f.T_w_c * T_b_c.inverse();
      StampedPose p;
      p.t_ns = t_ns;
      p.p_w_b = T_w_b.translation();
      p.q_w_b = Eigen::Quaterniond(T_w_b.linear());
      estimate.push_back(p);
      truth.push_back(testing::InterpolatePose(*gt_, t_ns));
    }
    s.mean_rot_deg /= std::max(s.tracked, 1);
    s.mean_trans_mm /= std::max(s.tracked, 1);
    const Alignment a = Align(estimate, truth, AlignmentMode::kSe3);
    s.ate_m = ComputeAte(a.Apply(estimate), truth).translation.rmse;
    s.summary = odometry.summary();
    return s;
  }

  static void Print(const char* name, const RunStats& s) {
    std::printf(
        "%s: %d tracked, %d keyframes, %d lost; frame to keyframe mean %.3f "
        "deg %.2f mm, max %.3f deg %.2f mm; ATE %.2f mm\n",
        name, s.tracked, s.summary.keyframes, s.summary.lost, s.mean_rot_deg,
        s.mean_trans_mm, s.max_rot_deg, s.max_trans_mm, s.ate_m * 1e3);
  }

  static testing::StereoSequence* seq_;
  static Trajectory* gt_;
  static std::vector<cv::Mat> left_, right_;
};

testing::StereoSequence* MH01Motion::seq_ = nullptr;
Trajectory* MH01Motion::gt_ = nullptr;
std::vector<cv::Mat> MH01Motion::left_, MH01Motion::right_;

// The default options (the notes' weight), run once for both tests.
const RunStats& Weighted() {
  static const RunStats s = MH01Motion::Run(DirectOdometryOptions());
  return s;
}

TEST_F(MH01Motion, TracksRealMotionAgainstGroundTruth) {
  const RunStats& s = Weighted();
  Print("weighted (the notes)", s);
  EXPECT_EQ(s.summary.frames, static_cast<int>(kFrames));
  EXPECT_EQ(s.summary.lost, 0);
  EXPECT_EQ(s.tracked, static_cast<int>(kFrames) - 1);
  EXPECT_GT(s.summary.keyframes, 1);
  // Measured: mean 0.040 deg 4.1 mm, max 0.073 deg 8.9 mm, ATE 2.7 mm.
  EXPECT_LT(s.mean_rot_deg, 0.1);
  EXPECT_LT(s.mean_trans_mm, 6.0);
  EXPECT_LT(s.max_rot_deg, 0.2);
  EXPECT_LT(s.max_trans_mm, 15.0);
  EXPECT_LT(s.ate_m, 0.005);
}

// The issue asks whether the notes' weight lowers the error against the
// unweighted alignment. Measured here: the trajectory's ATE, yes (2.7 against
// 3.0 mm); the mean frame-to-keyframe error, no (4.08 against 4.04 mm, the
// same within noise): near a keyframe the motion is small, so df/drho and
// with it the weight's depth term are small.
TEST_F(MH01Motion, VarianceWeightAgainstUnweighted) {
  DirectOdometryOptions unweighted;
  unweighted.tracker.variance_weight = false;
  const RunStats& w = Weighted();
  const RunStats u = Run(unweighted);
  Print("weighted (the notes)", w);
  Print("unweighted", u);
  EXPECT_EQ(u.summary.lost, 0);
  EXPECT_LT(w.ate_m, u.ate_m);
  EXPECT_LT(std::abs(w.mean_trans_mm - u.mean_trans_mm), 0.5);
}

TEST(DirectOdometry, BadInput) {
  const testing::StereoSequence seq(testing::SharedData("euroc_V1_01_first5s"));
  DirectOdometry odometry(seq.cam0, seq.cam1, DirectOdometryOptions());
  const cv::Mat left = testing::ReadGrey(seq.left[0]);
  const cv::Mat right = testing::ReadGrey(seq.right[0]);
  // A wrong size or type throws (callers skip and count such images).
  EXPECT_THROW(odometry.Process(0, left(cv::Rect(0, 0, 100, 100)), right),
               std::invalid_argument);
  cv::Mat as_float;
  left.convertTo(as_float, CV_32F);
  EXPECT_THROW(odometry.Process(0, as_float, right), std::invalid_argument);
  // No right image: counted, tracked on the left alone, not a keyframe.
  EXPECT_TRUE(odometry.Process(seq.left[0].t_ns, left, right).keyframe);
  const DirectFrame f = odometry.Process(
      seq.left[1].t_ns, testing::ReadGrey(seq.left[1]), cv::Mat());
  EXPECT_TRUE(f.tracked);
  EXPECT_FALSE(f.keyframe);
  EXPECT_EQ(odometry.summary().mono_frames, 1);
  // The vehicle stands still.
  EXPECT_LT(f.T_w_c.translation().norm(), 0.005);
  DirectOdometryOptions bad;
  bad.min_overlap = 1.5;
  EXPECT_THROW(DirectOdometry(seq.cam0, seq.cam1, bad), std::invalid_argument);
}

}  // namespace
}  // namespace vio
