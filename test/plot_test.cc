#include "eval/plot.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>
#include <vector>

#include "eval/eval_error.h"
#include "test/testing/trajectories.h"

namespace vio {
namespace {

// Pixels of (about) this BGR colour in the image.
int CountColour(const cv::Mat& image, const cv::Vec3b& bgr) {
  int count = 0;
  for (int r = 0; r < image.rows; ++r) {
    for (int c = 0; c < image.cols; ++c) {
      const cv::Vec3b p = image.at<cv::Vec3b>(r, c);
      if (std::abs(p[0] - bgr[0]) + std::abs(p[1] - bgr[1]) +
              std::abs(p[2] - bgr[2]) <
          30) {
        ++count;
      }
    }
  }
  return count;
}

TEST(Plot, WritesAPngWithBothTrajectoriesAndTheErrorCurve) {
  const Trajectory gt = testing::Lissajous(200);
  Trajectory est = gt;
  for (StampedPose& p : est) p.p_w_b.x() += 0.3;  // visibly apart
  std::vector<double> error_m;
  for (size_t i = 0; i < gt.size(); ++i)
    error_m.push_back(0.3 + 0.1 * std::sin(0.1 * i));
  const std::string path = ::testing::TempDir() + "plot_test.png";
  std::remove(path.c_str());
  PlotOptions options;
  options.width_px = 800;
  options.height_px = 900;
  options.title = "plot_test";
  WriteEvaluationPlot(path, gt, est, error_m, options);
  const cv::Mat image = cv::imread(path);
  ASSERT_FALSE(image.empty());
  EXPECT_EQ(image.cols, 800);
  EXPECT_EQ(image.rows, 900);
  // The estimate (blue), the ground truth (grey) and the error (red) are
  // drawn with hundreds of pixels each, not just the legend's.
  EXPECT_GT(CountColour(image, {200, 110, 0}), 500);
  EXPECT_GT(CountColour(image, {150, 150, 150}), 500);
  EXPECT_GT(CountColour(image, {40, 40, 210}), 200);
}

TEST(Plot, BadArgumentsAndUnwritablePathsAreErrors) {
  const Trajectory gt = testing::Lissajous(10);
  const std::vector<double> e(10, 0.0);
  const std::string ok = ::testing::TempDir() + "plot_test_small.png";
  EXPECT_THROW(
      WriteEvaluationPlot(ok, gt, Trajectory(gt.begin(), gt.end() - 1), e),
      std::invalid_argument);
  EXPECT_THROW(WriteEvaluationPlot(ok, {}, {}, {}), std::invalid_argument);
  PlotOptions tiny;
  tiny.width_px = 100;
  EXPECT_THROW(WriteEvaluationPlot(ok, gt, gt, e, tiny), std::invalid_argument);
  EXPECT_THROW(
      WriteEvaluationPlot(::testing::TempDir() + "no_dir/p.png", gt, gt, e),
      EvalError);
  EXPECT_THROW(
      WriteEvaluationPlot(::testing::TempDir() + "p.unknown", gt, gt, e),
      EvalError);
}

}  // namespace
}  // namespace vio
