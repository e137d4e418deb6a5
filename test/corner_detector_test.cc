// CornerDetector (frontend/corner_detector.h) against cv::goodFeaturesToTrack
// on real V1_01 images: with the tracker's kind of mask (discs around
// existing features) and with an open image, the same corners in the same
// order; bad input is refused.

#include "frontend/corner_detector.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <vector>

#include "test/testing/euroc_v1_01.h"

namespace vio {
namespace {

constexpr double kQuality = 0.002;  // the shipped configs' corner_quality
constexpr double kMinDistance = 30.0;

// The share of `expected`'s corners found at exactly the same place and rank
// by `got`.
double SameRank(const std::vector<cv::Point2f>& expected,
                const std::vector<cv::Point2f>& got) {
  if (expected.empty()) return got.empty() ? 1.0 : 0.0;
  size_t same = 0;
  for (size_t i = 0; i < expected.size() && i < got.size(); ++i) {
    same += expected[i] == got[i];
  }
  return static_cast<double>(same) / expected.size();
}

TEST(CornerDetector, FindsTheCornersOfGoodFeaturesToTrackInTheMaskGaps) {
  const cv::Mat image = testing::V101Image(0, 20);
  ASSERT_FALSE(image.empty());
  // Discs of min_distance around 120 corners of the image, as the tracker
  // masks its live tracks: a few gaps stay open.
  std::vector<cv::Point2f> tracks;
  cv::goodFeaturesToTrack(image, tracks, 120, kQuality, kMinDistance);
  cv::Mat mask(image.size(), CV_8UC1, cv::Scalar(255));
  for (const cv::Point2f& p : tracks) {
    cv::circle(mask, cv::Point(cvRound(p.x), cvRound(p.y)),
               static_cast<int>(kMinDistance), cv::Scalar(0), cv::FILLED);
  }
  std::vector<cv::Point2f> expected;
  cv::goodFeaturesToTrack(image, expected, 40, kQuality, kMinDistance, mask);
  ASSERT_GE(expected.size(), 10u);  // not vacuous: there are gaps to fill

  CornerDetector detector;
  const std::vector<cv::Point2f> got =
      detector.Detect(image, mask, 40, kQuality, kMinDistance);
  EXPECT_EQ(got.size(), expected.size());
  EXPECT_EQ(SameRank(expected, got), 1.0);
  // The point of it: most of the image was not filtered.
  EXPECT_LT(detector.computed_share(), 0.8);
}

TEST(CornerDetector, OpenImageGivesTheCornersOfGoodFeaturesToTrack) {
  for (int k : {0, 50, 94}) {
    const cv::Mat image = testing::V101Image(0, k);
    ASSERT_FALSE(image.empty());
    const cv::Mat open(image.size(), CV_8UC1, cv::Scalar(255));
    std::vector<cv::Point2f> expected;
    cv::goodFeaturesToTrack(image, expected, 150, kQuality, kMinDistance, open);
    CornerDetector detector(48);
    const std::vector<cv::Point2f> got =
        detector.Detect(image, open, 150, kQuality, kMinDistance);
    EXPECT_EQ(got.size(), expected.size()) << "image " << k;
    EXPECT_EQ(SameRank(expected, got), 1.0) << "image " << k;
    EXPECT_GE(detector.computed_share(), 1.0);
  }
}

TEST(CornerDetector, ClosedMaskGivesNoCornersAndBadInputThrows) {
  const cv::Mat image = testing::V101Image(0, 0);
  CornerDetector detector;
  EXPECT_TRUE(detector
                  .Detect(image, cv::Mat::zeros(image.size(), CV_8UC1), 10,
                          kQuality, kMinDistance)
                  .empty());
  EXPECT_EQ(detector.computed_share(), 0.0);
  EXPECT_THROW(detector.Detect(image, cv::Mat(10, 10, CV_8UC1), 10, kQuality,
                               kMinDistance),
               std::invalid_argument);
  cv::Mat colour;
  cv::cvtColor(image, colour, cv::COLOR_GRAY2BGR);
  EXPECT_THROW(detector.Detect(colour, cv::Mat(image.size(), CV_8UC1), 10,
                               kQuality, kMinDistance),
               std::invalid_argument);
  EXPECT_THROW(CornerDetector(0), std::invalid_argument);
}

}  // namespace
}  // namespace vio
