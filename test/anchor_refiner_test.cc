// Drift-free tracking (frontend/anchor_refiner.h) on a real EuRoC frame
// warped by known homographies that zoom and roll the image, as approaching
// a wall and rolling do: frame-to-frame LK alone slides, the affine
// refinement against the first appearance keeps every track on its point.

#include "frontend/anchor_refiner.h"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cstring>
#include <map>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>
#include <opencv2/imgproc.hpp>
#include <random>
#include <vector>

#include "frontend/feature_tracker.h"
#include "test/testing/euroc_v1_01.h"

namespace vio {
namespace {

Eigen::Vector2d Apply(const Eigen::Matrix3d& H, const Eigen::Vector2d& uv) {
  return (H * uv.homogeneous()).hnormalized();
}

double Percentile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return v[static_cast<size_t>(q * (v.size() - 1))];
}

class ZoomingRealFrames : public ::testing::Test {
 protected:
  void SetUp() override {
    const CameraCalibration cam0 = testing::V101Cam0();
    const cv::Mat raw = testing::V101Image(0, 0);
    ASSERT_FALSE(raw.empty()) << "cannot read " << testing::V101Dir();
    cv::Mat K, D;
    Eigen::Matrix3d K_e;
    K_e << cam0.fx, 0, cam0.cx, 0, cam0.fy, cam0.cy, 0, 0, 1;
    cv::eigen2cv(K_e, K);
    cv::eigen2cv(Eigen::Vector4d(cam0.distortion_coefficients), D);
    cv::undistort(raw, undistorted_, K, D);
    pinhole_ = cam0;
    pinhole_.distortion = DistortionModel::kNone;
    centre_ = Eigen::Vector2d(cam0.cx, cam0.cy);
  }

  // Frame k: zoomed by 1.5 % and rolled by 0.8 degrees per frame about the
  // image centre, and shifted by (1.5, -0.5) px per frame.
  Eigen::Matrix3d Homography(int k) const {
    const double s = std::pow(1.015, k), a = 0.014 * k;
    Eigen::Matrix3d H = Eigen::Matrix3d::Identity();
    H.topLeftCorner<2, 2>() << s * std::cos(a), -s * std::sin(a),
        s * std::sin(a), s * std::cos(a);
    H.topRightCorner<2, 1>() = centre_ - H.topLeftCorner<2, 2>() * centre_ +
                               k * Eigen::Vector2d(1.5, -0.5);
    return H;
  }

  cv::Mat Warped(int k) const {
    cv::Mat H, out;
    cv::eigen2cv(Homography(k), H);
    cv::warpPerspective(undistorted_, out, H, undistorted_.size(),
                        cv::INTER_LINEAR, cv::BORDER_CONSTANT, cv::Scalar(0));
    return out;
  }

  bool FromInside(int k, const Eigen::Vector2d& uv) const {
    const Eigen::Vector2d src = Apply(Homography(k).inverse(), uv);
    const double m = 30.0;
    return src.x() > m && src.y() > m && src.x() < pinhole_.width - m &&
           src.y() < pinhole_.height - m;
  }

  // Errors of the tracks of 16 frames against the homography, of sightings
  // at least 8 frames after their first.
  std::vector<double> LateErrors(const FeatureTrackerOptions& options) const {
    FeatureTracker tracker(CameraModel(pinhole_), options);
    std::map<int64_t, std::pair<int, Eigen::Vector2d>> first;
    std::vector<double> errors;
    for (int k = 0; k < 16; ++k) {
      for (const FeatureObservation& o : tracker.Track(Warped(k))) {
        const auto it = first.find(o.feature_id);
        if (it == first.end()) {
          first[o.feature_id] = {k, o.uv};
          continue;
        }
        const auto& [j, uv_j] = it->second;
        if (k - j < 8 || !FromInside(j, uv_j) || !FromInside(k, o.uv)) {
          continue;
        }
        const Eigen::Vector2d expected =
            Apply(Homography(k) * Homography(j).inverse(), uv_j);
        errors.push_back((o.uv - expected).norm());
      }
    }
    return errors;
  }

  cv::Mat undistorted_;
  CameraCalibration pinhole_;
  Eigen::Vector2d centre_;
};

TEST_F(ZoomingRealFrames, AnchorRefinementKeepsTracksOnTheirPoints) {
  FeatureTrackerOptions options;
  options.fundamental_baseline_frames = 0;  // the homography alone is judged
  options.anchor_refinement = true;
  const std::vector<double> refined = LateErrors(options);
  options.anchor_refinement = false;
  const std::vector<double> plain = LateErrors(options);
  ASSERT_GT(refined.size(), 300u);
  ASSERT_GT(plain.size(), 300u);
  std::printf(
      "8+ frames after the first sighting: refined median %.3f p95 %.3f px "
      "(%zu), frame to frame median %.3f p95 %.3f px (%zu)\n",
      Percentile(refined, 0.5), Percentile(refined, 0.95), refined.size(),
      Percentile(plain, 0.5), Percentile(plain, 0.95), plain.size());
  EXPECT_LT(Percentile(refined, 0.5), 0.1);
  EXPECT_LT(Percentile(refined, 0.95), 0.5);
  // Without the refinement the same tracks slide (the claim the refinement
  // answers).
  EXPECT_GT(Percentile(plain, 0.5), 2.0 * Percentile(refined, 0.5));
}

TEST_F(ZoomingRealFrames, APatchThatNoLongerLooksLikeItsAnchorIsDropped) {
  FeatureTrackerOptions options;
  AnchorRefiner refiner(options);
  cv::Mat image;
  undistorted_.convertTo(image, CV_32F);
  const cv::Point2f a(200.5f, 150.25f), b(400.0f, 300.0f);
  refiner.Add(1, image, a);
  refiner.Add(2, image, b);
  // Point 2's neighbourhood is replaced by another part of the image.
  cv::Mat changed = image.clone();
  image(cv::Rect(100, 50, 41, 41)).copyTo(changed(cv::Rect(380, 280, 41, 41)));
  std::vector<cv::Point2f> points = {a + cv::Point2f(0.6f, -0.4f), b};
  const std::vector<AnchorResult> results =
      refiner.Refine(changed, {1, 2}, &points);
  ASSERT_EQ(results.size(), 2u);
  EXPECT_EQ(results[0], AnchorResult::kRefined);
  EXPECT_LT(cv::norm(points[0] - a), 0.02);  // pulled back onto its anchor
  EXPECT_EQ(results[1], AnchorResult::kDropped);
  refiner.Keep({1});
  EXPECT_THROW(refiner.Refine(changed, {2}, &points), std::out_of_range);
}

// The refiner's sampling as it was written before it was made faster: the
// point from Eigen's product, then a bilinear read with clamped borders.
float PlainBilinear(const cv::Mat& image, float u, float v) {
  u = std::clamp(u, 0.0f, static_cast<float>(image.cols - 1));
  v = std::clamp(v, 0.0f, static_cast<float>(image.rows - 1));
  const int x = std::min(static_cast<int>(u), image.cols - 2);
  const int y = std::min(static_cast<int>(v), image.rows - 2);
  const float a = u - x, b = v - y;
  const float* r0 = image.ptr<float>(y) + x;
  const float* r1 = image.ptr<float>(y + 1) + x;
  return (1 - b) * ((1 - a) * r0[0] + a * r0[1]) +
         b * ((1 - a) * r1[0] + a * r1[1]);
}

// Warps that scale, turn and shear, at points inside the image, near its
// borders and beyond them: every sample equals the plain expressions' bit
// for bit (==, not near), through both the vectorised inner path and the
// clamped one.
TEST(SampleAffinePatch, EqualsThePlainPerPixelExpressionsBitForBit) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<float> grey(0.0f, 255.0f);
  cv::Mat image(120, 160, CV_32F);
  for (int r = 0; r < image.rows; ++r) {
    for (int c = 0; c < image.cols; ++c) image.at<float>(r, c) = grey(rng);
  }
  std::uniform_real_distribution<float> entry(-0.6f, 0.6f);
  std::uniform_real_distribution<float> u_dist(-15.0f, 175.0f);
  std::uniform_real_distribution<float> v_dist(-15.0f, 135.0f);
  std::vector<float> buffer;
  Eigen::VectorXf samples;
  int inside = 0, clamped = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const int half = trial % 3 == 0 ? 10 : 1 + trial % 7;
    Eigen::Matrix2f M = Eigen::Matrix2f::Identity();
    if (trial % 5 != 0) {
      M += Eigen::Matrix2f::NullaryExpr([&] { return entry(rng); });
    }
    const Eigen::Vector2f t(u_dist(rng), v_dist(rng));
    SampleAffinePatch(image, M, t, half, &buffer, &samples);
    const int side = 2 * half + 1;
    ASSERT_EQ(samples.size(), side * side);
    bool all_inside = true;
    for (int i = 0; i < side; ++i) {
      for (int j = 0; j < side; ++j) {
        const Eigen::Vector2f q =
            M * Eigen::Vector2f(static_cast<float>(j - half),
                                static_cast<float>(i - half)) +
            t;
        all_inside = all_inside && q.x() >= 1 && q.y() >= 1 &&
                     q.x() < image.cols - 2 && q.y() < image.rows - 2;
        const float expected = PlainBilinear(image, q.x(), q.y());
        ASSERT_EQ(std::memcmp(&expected, &samples[i * side + j], 4), 0)
            << "trial " << trial << " pixel (" << i << ", " << j
            << "): " << expected << " vs " << samples[i * side + j];
      }
    }
    ++(all_inside ? inside : clamped);
  }
  EXPECT_GT(inside, 500);
  EXPECT_GT(clamped, 500);
}

}  // namespace
}  // namespace vio
