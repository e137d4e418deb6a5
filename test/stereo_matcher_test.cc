#include "frontend/stereo_matcher.h"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>
#include <opencv2/imgproc.hpp>
#include <set>
#include <string>
#include <vector>

#include "frontend/feature_tracker.h"
#include "test/testing/euroc_v1_01.h"

namespace vio {
namespace {

double Median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

// The pair's geometry computed here independently of the matcher: OpenCV's
// own undistortion (cv::undistortPoints) and T_c0_c1 = T_b_c0^-1 T_b_c1 from
// the 4x4 extrinsics.
class RealStereoPairs : public ::testing::Test {
 protected:
  void SetUp() override {
    cam0_ = testing::V101Cam0();
    cam1_ = testing::V101Cam1();
    Eigen::Matrix4d T_b_c0 = Eigen::Matrix4d::Identity(), T_b_c1 = T_b_c0;
    T_b_c0.topLeftCorner<3, 3>() = cam0_.q_b_c.toRotationMatrix();
    T_b_c0.topRightCorner<3, 1>() = cam0_.t_b_c;
    T_b_c1.topLeftCorner<3, 3>() = cam1_.q_b_c.toRotationMatrix();
    T_b_c1.topRightCorner<3, 1>() = cam1_.t_b_c;
    T_c0_c1_ = T_b_c0.inverse() * T_b_c1;
  }

  static cv::Point2d Undistorted(const CameraCalibration& c, double u,
                                 double v) {
    const cv::Matx33d K(c.fx, 0, c.cx, 0, c.fy, c.cy, 0, 0, 1);
    const cv::Vec4d D(
        c.distortion_coefficients[0], c.distortion_coefficients[1],
        c.distortion_coefficients[2], c.distortion_coefficients[3]);
    std::vector<cv::Point2d> in{{u, v}}, out;
    cv::undistortPoints(
        in, out, K, D, cv::noArray(), cv::noArray(),
        cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 100,
                         1e-14));
    return out[0];
  }

  // Epipolar distance of the right match [px] and the depth in cam0 [m]
  // (midpoint of the two rays: lambda0 f0 = lambda1 R f1 + t).
  void Geometry(const Eigen::Vector2d& uv0, const Eigen::Vector2d& uv1,
                double* epipolar_px, double* depth) const {
    const cv::Point2d a = Undistorted(cam0_, uv0.x(), uv0.y());
    const cv::Point2d b = Undistorted(cam1_, uv1.x(), uv1.y());
    const Eigen::Vector3d f0(a.x, a.y, 1.0), f1(b.x, b.y, 1.0);
    const Eigen::Matrix3d R = T_c0_c1_.topLeftCorner<3, 3>();
    const Eigen::Vector3d t = T_c0_c1_.topRightCorner<3, 1>();
    // Distance of f1 to the epipolar line, taken in cam1: line l = E^T f0.
    const Eigen::Matrix3d tx = (Eigen::Matrix3d() << 0, -t.z(), t.y(), t.z(), 0,
                                -t.x(), -t.y(), t.x(), 0)
                                   .finished();
    const Eigen::Vector3d l = (tx * R).transpose() * f0;
    *epipolar_px =
        std::abs(l.dot(f1)) / l.head<2>().norm() * 0.5 * (cam1_.fx + cam1_.fy);
    Eigen::Matrix<double, 3, 2> A;
    A << f0, -(R * f1);
    const Eigen::Vector2d lambda = A.colPivHouseholderQr().solve(t);
    *depth = lambda[0];
  }

  // Shi-Tomasi features of the left image of pair `index`.
  std::vector<FeatureObservation> LeftFeatures(const cv::Mat& left) const {
    FeatureTracker tracker{CameraModel(cam0_), FeatureTrackerOptions()};
    return tracker.Track(left);
  }

  CameraCalibration cam0_, cam1_;
  Eigen::Matrix4d T_c0_c1_;
};

TEST_F(RealStereoPairs, MatchesAgreeWithTheCalibratedEpipolarGeometry) {
  // The epipolar check off: do raw LK matches (reverse-checked) agree with
  // the calibration?
  StereoMatcherOptions options;
  options.max_epipolar_px = 1e6;
  const StereoMatcher matcher(CameraModel(cam0_), CameraModel(cam1_), options);
  std::vector<double> errors;
  size_t left_total = 0;
  for (size_t index : {0, 30, 60, 90}) {
    const cv::Mat left = testing::V101Image(0, index);
    const cv::Mat right = testing::V101Image(1, index);
    ASSERT_FALSE(left.empty() || right.empty());
    const auto features = LeftFeatures(left);
    left_total += features.size();
    std::map<int64_t, Eigen::Vector2d> uv0;
    for (const auto& o : features) uv0[o.feature_id] = o.uv;
    for (const FeatureObservation& o : matcher.Match(left, right, features)) {
      double epipolar = 0, depth = 0;
      Geometry(uv0.at(o.feature_id), o.uv, &epipolar, &depth);
      errors.push_back(epipolar);
      EXPECT_NEAR(matcher.EpipolarErrorPx(uv0.at(o.feature_id), o.uv), epipolar,
                  1e-3);
    }
  }
  std::sort(errors.begin(), errors.end());
  std::printf("raw matches %zu of %zu: epipolar median %.3f px, p90 %.3f\n",
              errors.size(), left_total, Median(errors),
              errors[errors.size() * 9 / 10]);
  ASSERT_GT(errors.size(), left_total / 2);
  EXPECT_LT(Median(errors), 1.0);
}

TEST_F(RealStereoPairs, MatchesGivePlausibleDepths) {
  const StereoMatcher matcher{CameraModel(cam0_), CameraModel(cam1_),
                              StereoMatcherOptions()};
  std::vector<double> depths;
  size_t left_total = 0;
  for (size_t index : {0, 45, 94}) {
    const cv::Mat left = testing::V101Image(0, index);
    const cv::Mat right = testing::V101Image(1, index);
    const auto features = LeftFeatures(left);
    left_total += features.size();
    std::map<int64_t, Eigen::Vector2d> uv0;
    for (const auto& o : features) uv0[o.feature_id] = o.uv;
    StereoStats stats;
    for (const FeatureObservation& o :
         matcher.Match(left, right, features, &stats)) {
      EXPECT_EQ(o.camera, 1);
      double epipolar = 0, depth = 0;
      Geometry(uv0.at(o.feature_id), o.uv, &epipolar, &depth);
      EXPECT_LE(epipolar, 1.0 + 1e-3);
      depths.push_back(depth);
    }
    std::printf(
        "pair %zu: %d matched, lost flow %d reverse %d epipolar %d "
        "depth %d\n",
        index, stats.matched, stats.lost_flow, stats.lost_reverse,
        stats.rejected_epipolar, stats.rejected_depth);
  }
  const auto plausible =
      std::count_if(depths.begin(), depths.end(),
                    [](double d) { return d > 0.5 && d < 15.0; });
  std::printf("%zu matches of %zu, %ld in 0.5-15 m, median depth %.2f m\n",
              depths.size(), left_total, plausible, Median(depths));
  EXPECT_GT(depths.size(), 0.45 * left_total);  // measured 0.54
  EXPECT_GE(plausible, 0.9 * depths.size());
  EXPECT_GT(Median(depths), 1.0);
  EXPECT_LT(Median(depths), 8.0);
}

TEST_F(RealStereoPairs, EpipolarCheckRejectsAShiftedRightImage) {
  // The right image moved down by 4 px: LK follows the shift, so matches are
  // consistent photometrically but 4 px off their epipolar lines.
  const StereoMatcher matcher{CameraModel(cam0_), CameraModel(cam1_),
                              StereoMatcherOptions()};
  const cv::Mat left = testing::V101Image(0, 0);
  const cv::Mat right = testing::V101Image(1, 0);
  cv::Mat shifted;
  const cv::Mat M = (cv::Mat_<double>(2, 3) << 1, 0, 0, 0, 1, 4);
  cv::warpAffine(right, shifted, M, right.size());
  const auto features = LeftFeatures(left);
  StereoStats straight, moved;
  matcher.Match(left, right, features, &straight);
  matcher.Match(left, shifted, features, &moved);
  std::printf("straight: %d matched, %d off-epipolar; shifted: %d, %d\n",
              straight.matched, straight.rejected_epipolar, moved.matched,
              moved.rejected_epipolar);
  EXPECT_GT(moved.rejected_epipolar, 5 * moved.matched);
  EXPECT_GT(straight.matched, 5 * straight.rejected_epipolar);
}

TEST_F(RealStereoPairs, RightObservationsKeepTheLeftIds) {
  const StereoMatcher matcher{CameraModel(cam0_), CameraModel(cam1_),
                              StereoMatcherOptions()};
  const cv::Mat left = testing::V101Image(0, 10);
  const auto features = LeftFeatures(left);
  std::set<int64_t> left_ids;
  for (const auto& o : features) left_ids.insert(o.feature_id);
  std::set<int64_t> right_ids;
  for (const auto& o :
       matcher.Match(left, testing::V101Image(1, 10), features)) {
    EXPECT_EQ(o.camera, 1);
    EXPECT_TRUE(left_ids.count(o.feature_id));
    EXPECT_TRUE(right_ids.insert(o.feature_id).second);
  }
  EXPECT_THROW(matcher.Match(left, cv::Mat(), features), std::invalid_argument);
  EXPECT_THROW(matcher.Match(left, cv::Mat(100, 100, CV_8UC1), features),
               std::invalid_argument);
}

// Images prepared into buffers that held another pair (the replay reuses
// them from frame to frame) match exactly as freshly prepared ones.
TEST_F(RealStereoPairs, ReusedBuffersMatchAsFreshOnes) {
  const StereoMatcher matcher{CameraModel(cam0_), CameraModel(cam1_),
                              StereoMatcherOptions()};
  StereoImage left, right;
  matcher.PrepareLeft(testing::V101Image(0, 0), &left);
  matcher.PrepareRight(testing::V101Image(1, 0), &right);
  const cv::Mat left_image = testing::V101Image(0, 20);
  const cv::Mat right_image = testing::V101Image(1, 20);
  const auto features = LeftFeatures(left_image);
  const uchar* buffer = left.pyramid[0].datastart;
  matcher.PrepareLeft(left_image, &left);
  matcher.PrepareRight(right_image, &right);
  EXPECT_EQ(left.pyramid[0].datastart, buffer) << "the buffer was reused";
  StereoStats reused_stats, fresh_stats;
  const auto reused = matcher.Match(left, right, features, &reused_stats);
  const auto fresh =
      matcher.Match(left_image, right_image, features, &fresh_stats);
  ASSERT_GT(fresh.size(), 50u);
  ASSERT_EQ(reused.size(), fresh.size());
  for (size_t i = 0; i < fresh.size(); ++i) {
    EXPECT_EQ(reused[i].feature_id, fresh[i].feature_id);
    EXPECT_EQ(reused[i].uv, fresh[i].uv) << "match " << i;
  }
  EXPECT_EQ(reused_stats.lost_reverse, fresh_stats.lost_reverse);
}

// A start at each feature's own left pixel is where OpenCV starts a point
// without a guess: the same matches bit for bit. A start of the wrong size
// is refused, naming both sizes.
TEST_F(RealStereoPairs, StartAtTheLeftPixelsMatchesAsWithoutAStart) {
  const StereoMatcher matcher{CameraModel(cam0_), CameraModel(cam1_),
                              StereoMatcherOptions()};
  const cv::Mat left = testing::V101Image(0, 10);
  const StereoImage l = matcher.PrepareLeft(left);
  const StereoImage r = matcher.PrepareRight(testing::V101Image(1, 10));
  const std::vector<FeatureObservation> features = LeftFeatures(left);
  std::vector<cv::Point2f> start;
  for (const FeatureObservation& o : features) {
    start.emplace_back(static_cast<float>(o.uv.x()),
                       static_cast<float>(o.uv.y()));
  }
  StereoStats plain_stats, started_stats;
  const std::vector<FeatureObservation> plain =
      matcher.Match(l, r, features, &plain_stats);
  const std::vector<FeatureObservation> started =
      matcher.Match(l, r, features, start, &started_stats);
  ASSERT_GT(plain.size(), 50u);
  ASSERT_EQ(started.size(), plain.size());
  for (size_t i = 0; i < plain.size(); ++i) {
    EXPECT_EQ(started[i].feature_id, plain[i].feature_id);
    EXPECT_EQ(started[i].uv, plain[i].uv);  // ==, bit for bit
  }
  EXPECT_EQ(started_stats.lost_reverse, plain_stats.lost_reverse);
  start.pop_back();
  try {
    matcher.Match(l, r, features, start);
    FAIL() << "a start of the wrong size was taken";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(std::to_string(start.size()) +
                                         " start pixels for " +
                                         std::to_string(features.size())),
              std::string::npos)
        << e.what();
  }
}

// The reverse check on fewer pyramid levels changes only which matches pass
// it: the left -> right LK is the same, so a match both settings accept is
// the same pixel (==). On these pairs the check on full resolution alone
// lets a few more matches through (the coarse levels can carry a patch
// that differs away from its start).
TEST_F(RealStereoPairs, ReverseCheckLevelsChangeOnlyWhichMatchesPass) {
  StereoMatcherOptions all_levels;
  all_levels.reverse_pyramid_levels = all_levels.klt.pyramid_levels;
  const StereoMatcher coarse{CameraModel(cam0_), CameraModel(cam1_),
                             all_levels};
  const StereoMatcher fine{CameraModel(cam0_), CameraModel(cam1_),
                           StereoMatcherOptions()};
  size_t n_coarse = 0, n_fine = 0, common = 0;
  for (size_t k : {0u, 30u, 60u, 90u}) {
    const cv::Mat left = testing::V101Image(0, k);
    const cv::Mat right = testing::V101Image(1, k);
    const auto features = LeftFeatures(left);
    const auto a = coarse.Match(left, right, features);
    const auto b = fine.Match(left, right, features);
    std::map<int64_t, Eigen::Vector2d> by_id;
    for (const FeatureObservation& o : a) by_id[o.feature_id] = o.uv;
    for (const FeatureObservation& o : b) {
      const auto it = by_id.find(o.feature_id);
      if (it == by_id.end()) continue;
      EXPECT_EQ(it->second, o.uv) << "feature " << o.feature_id;
      ++common;
    }
    n_coarse += a.size();
    n_fine += b.size();
  }
  std::printf("reverse check on 4 levels: %zu matches, on 1: %zu, common %zu\n",
              n_coarse, n_fine, common);
  EXPECT_GT(common, 200u);
  EXPECT_NE(n_fine, n_coarse) << "the option changed nothing";
  EXPECT_LT(std::abs(static_cast<double>(n_fine) - n_coarse), 0.1 * n_coarse);
}

}  // namespace
}  // namespace vio
