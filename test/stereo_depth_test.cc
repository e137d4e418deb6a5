// Semi-dense stereo depth (frontend/stereo_depth.h) on the real V1_01 pair:
// against the depths of the frontend's independent KLT stereo matches, its
// variance against the spread between two still frames, and the depth
// pyramid of the keyframe.

#include "frontend/stereo_depth.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "frontend/direct_keyframe.h"
#include "frontend/stereo_matcher.h"
#include "testing/direct_sequence.h"

namespace vio {
namespace {

double Median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

struct Pair {
  ImagePyramid left, right;
};

Pair LoadPair(const testing::StereoSequence& seq, size_t index) {
  const PinholeUndistorter u0(seq.cam0), u1(seq.cam1);
  return {ImagePyramid(u0.Undistort(testing::ReadGrey(seq.left[index])),
                       u0.pinhole(), 3),
          ImagePyramid(u1.Undistort(testing::ReadGrey(seq.right[index])),
                       u1.pinhole(), 3)};
}

std::map<int, DepthPoint> ByPixel(const std::vector<DepthPoint>& points,
                                  int width) {
  std::map<int, DepthPoint> out;
  for (const DepthPoint& p : points) {
    out[static_cast<int>(p.uv.y()) * width + static_cast<int>(p.uv.x())] = p;
  }
  return out;
}

TEST(StereoDepth, AgreesWithTheFrontendsKltStereoMatches) {
  const testing::StereoSequence seq(testing::SharedData("euroc_V1_01_first5s"));
  const Pair pair = LoadPair(seq, 0);
  StereoDepthStats stats;
  const std::vector<DepthPoint> points =
      StereoInverseDepth(pair.left.level(0), pair.right.level(0), seq.T_c1_c0(),
                         0, StereoDepthOptions(), &stats);
  EXPECT_EQ(stats.candidates, stats.along_edge + stats.out_of_view +
                                  stats.low_ncc + stats.ambiguous +
                                  stats.accepted);
  EXPECT_EQ(stats.accepted, static_cast<int>(points.size()));
  const int width = pair.left.level(0).image->width();
  const std::map<int, DepthPoint> by_pixel = ByPixel(points, width);

  // Independent depths: Shi-Tomasi corners of the raw cam0 image matched by
  // KLT into cam1 (frontend/stereo_matcher.h) and triangulated.
  const cv::Mat raw0 = testing::ReadGrey(seq.left[0]);
  const cv::Mat raw1 = testing::ReadGrey(seq.right[0]);
  std::vector<cv::Point2f> corners;
  cv::goodFeaturesToTrack(raw0, corners, 300, 0.01, 15);
  std::vector<FeatureObservation> observations;
  for (size_t i = 0; i < corners.size(); ++i) {
    FeatureObservation o;
    o.feature_id = static_cast<int64_t>(i);
    o.uv = Eigen::Vector2d(corners[i].x, corners[i].y);
    observations.push_back(o);
  }
  const CameraModel cam0(seq.cam0), cam1(seq.cam1);
  const StereoMatcher matcher(cam0, cam1, StereoMatcherOptions());
  const Pinhole& K = pair.left.level(0).camera;
  std::vector<double> relative;
  for (const FeatureObservation& m : matcher.Match(raw0, raw1, observations)) {
    Eigen::Vector2d xy0, xy1;
    double depth = 0.0;
    if (!cam0.PixelToNormalized(observations[m.feature_id].uv, &xy0) ||
        !cam1.PixelToNormalized(m.uv, &xy1) ||
        !matcher.TriangulateDepth(xy0, xy1, &depth)) {
      continue;
    }
    // The semi-dense point at the corner's undistorted pixel, if any.
    const Eigen::Vector2d uv = K.Project(xy0.homogeneous());
    const int u = static_cast<int>(std::lround(uv.x()));
    const int v = static_cast<int>(std::lround(uv.y()));
    const auto it = by_pixel.find(v * width + u);
    if (it == by_pixel.end()) continue;
    relative.push_back(std::abs(1.0 / it->second.rho - depth) / depth);
  }
  ASSERT_GT(relative.size(), 40u);
  std::sort(relative.begin(), relative.end());
  const double median = relative[relative.size() / 2];
  const double p90 = relative[relative.size() * 9 / 10];
  std::printf(
      "%zu points; %zu corners with a semi-dense depth: relative depth "
      "difference median %.4f, 90th percentile %.4f\n",
      points.size(), relative.size(), median, p90);
  EXPECT_LT(median, 0.02);
  EXPECT_LT(p90, 0.06);
}

// The vehicle stands still: pairs 0 and 40 see the same scene with other
// noise, so the difference of two depths of a pixel, over the square root of
// the sum of their variances, should look like a unit normal variable.
TEST(StereoDepth, VarianceMatchesTheSpreadBetweenTwoStillFrames) {
  const testing::StereoSequence seq(testing::SharedData("euroc_V1_01_first5s"));
  for (int level : {0, 1}) {
    std::vector<std::vector<DepthPoint>> depths;
    for (size_t frame : {size_t{0}, size_t{40}}) {
      const Pair pair = LoadPair(seq, frame);
      StereoDepthOptions options;
      options.sigma_epipolar_px = 0.0;
      options.sigma_intensity = 2.4;
      depths.push_back(StereoInverseDepth(pair.left.level(level),
                                          pair.right.level(level),
                                          seq.T_c1_c0(), level, options));
    }
    const std::map<int, DepthPoint> a = ByPixel(depths[0], 1000);
    std::vector<double> z;
    for (const DepthPoint& q : depths[1]) {
      const auto it = a.find(static_cast<int>(q.uv.y()) * 1000 +
                             static_cast<int>(q.uv.x()));
      if (it == a.end()) continue;
      z.push_back(std::abs(it->second.rho - q.rho) /
                  std::sqrt(it->second.variance + q.variance));
    }
    ASSERT_GT(z.size(), 1000u);
    const double median = Median(z);
    const double within2 =
        std::count_if(z.begin(), z.end(), [](double v) { return v < 2.0; }) /
        static_cast<double>(z.size());
    std::printf(
        "level %d: %zu pixels in both; |z| median %.3f (normal: 0.674), "
        "%.1f %% within 2 (normal: 95.4 %%)\n",
        level, z.size(), median, 100.0 * within2);
    EXPECT_GT(median, 0.674 / 2.0);
    EXPECT_LT(median, 0.674 * 2.0);
  }
}

// The coarser level: the inverse-variance mean of a 2 x 2 block, with the
// harmonic mean of the variances plus the block's spread.
TEST(StereoDepth, CoarserLevelTakesTheInverseVarianceMean) {
  // The smallest image a 2-level pyramid takes (levels of >= 8 x 8 px).
  std::vector<float> values(16 * 16);
  for (size_t i = 0; i < values.size(); ++i) values[i] = static_cast<float>(i);
  cv::Mat image(16, 16, CV_32F, values.data());
  const ImagePyramid pyramid(image, {20, 20, 7.5, 7.5}, 2);
  std::vector<DepthPoint> fine(3);
  fine[0].uv = {2, 2};  // block (1, 1)
  fine[0].rho = 0.5;
  fine[0].variance = 0.01;
  fine[1].uv = {3, 3};  // block (1, 1)
  fine[1].rho = 0.8;
  fine[1].variance = 0.04;
  fine[2].uv = {6, 1};  // block (3, 0)
  fine[2].rho = 0.25;
  fine[2].variance = 0.02;
  const std::vector<DepthPoint> coarse =
      CoarserDepthPoints(fine, pyramid.level(1));
  ASSERT_EQ(coarse.size(), 2u);
  // Row-major order: (3, 0) first.
  EXPECT_EQ(coarse[0].uv, Eigen::Vector2d(3, 0));
  EXPECT_DOUBLE_EQ(coarse[0].rho, 0.25);
  EXPECT_DOUBLE_EQ(coarse[0].variance, 0.02);
  EXPECT_EQ(coarse[1].uv, Eigen::Vector2d(1, 1));
  const double w0 = 100.0, w1 = 25.0;
  const double rho = (w0 * 0.5 + w1 * 0.8) / (w0 + w1);
  EXPECT_NEAR(coarse[1].rho, rho, 1e-12);
  const double spread =
      (w0 * std::pow(0.5 - rho, 2) + w1 * std::pow(0.8 - rho, 2)) / (w0 + w1);
  EXPECT_NEAR(coarse[1].variance, 2.0 / (w0 + w1) + spread, 1e-12);
  EXPECT_FLOAT_EQ(coarse[1].intensity, pyramid.level(1).image->At(1, 1));
}

TEST(StereoDepth, OptionsNameTheBadField) {
  StereoDepthOptions options;
  std::string message;
  EXPECT_TRUE(options.Validate(&message));
  options.max_depth_m = 0.2;
  EXPECT_FALSE(options.Validate(&message));
  EXPECT_EQ(message, "max_depth_m must be > min_depth_m (got 0.2)");
  options = StereoDepthOptions();
  options.min_ncc = 1.5;
  EXPECT_FALSE(options.Validate(&message));
  EXPECT_EQ(message, "min_ncc must be in (-1, 1) (got 1.5)");
}

}  // namespace
}  // namespace vio
