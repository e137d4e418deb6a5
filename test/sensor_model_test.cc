// The sensor model (render/sensor_model.h) against its own formulas, by
// Monte-Carlo: the noise has the standard deviation its options promise,
// vignetting falls to the corner gain, the gain scales and 8 bits saturate;
// and the sequence renderer's blur, gain walk and truth pose.

#include "render/sensor_model.h"

#include <gtest/gtest.h>

#include <cmath>

#include "dataset/simulator.h"
#include "render/scene.h"
#include "render/sequence_renderer.h"
#include "render/texture_atlas.h"
#include "test/testing/expect_error.h"

namespace vio {
namespace {

RenderOptions Plain() {
  RenderOptions o;
  o.vignetting_corner_gain = 1.0;
  o.read_noise_grey = 0.0;
  o.shot_noise_grey = 0.0;
  return o;
}

TEST(SensorModel, NoiseHasTheStandardDeviationItsOptionsSay) {
  RenderOptions o = Plain();
  o.read_noise_grey = 1.5;
  o.shot_noise_grey = 0.05;
  const CameraCalibration c = EurocCam0Calibration();
  const SensorModel sensor(c, o);
  for (const float level : {20.0f, 100.0f, 180.0f}) {
    const cv::Mat radiance(c.height, c.width, CV_32F, cv::Scalar(level));
    cv::Mat image;
    sensor.Expose(radiance, 1.0, 7, &image);
    cv::Scalar mean, std;
    cv::meanStdDev(image, mean, std);
    // Rounding to integers adds 1/12 grey^2 of variance.
    const double expected = std::sqrt(1.5 * 1.5 + 0.05 * level + 1.0 / 12);
    EXPECT_NEAR(mean[0], level, 0.02) << level;
    EXPECT_NEAR(std[0], expected, 0.02 * expected) << level;  // 361k pixels
  }
}

TEST(SensorModel, VignettingFallsToTheCornerGainAndGainScales) {
  RenderOptions o = Plain();
  o.vignetting_corner_gain = 0.6;
  const CameraCalibration c = EurocCam0Calibration();
  const SensorModel sensor(c, o);
  const cv::Mat& v = sensor.vignetting();
  // The farthest corner from the principal point (367, 248) is the top
  // right one, (751, 0).
  EXPECT_NEAR(v.at<float>(0, 751), 0.6, 1e-6);
  EXPECT_GT(v.at<float>(0, 0), 0.6);
  EXPECT_NEAR(v.at<float>(248, 367), 1.0, 1e-5);
  const cv::Mat radiance(c.height, c.width, CV_32F, cv::Scalar(200.0f));
  cv::Mat image;
  sensor.Expose(radiance, 0.5, 1, &image);
  EXPECT_EQ(image.at<uchar>(248, 367), 100);
  EXPECT_EQ(image.at<uchar>(0, 751), 60);
  sensor.Expose(radiance, 2.0, 1, &image);
  EXPECT_EQ(image.at<uchar>(248, 367), 255);  // saturates
  ExpectErrorContaining<std::invalid_argument>(
      [&] { sensor.Expose(cv::Mat(10, 10, CV_32F), 1.0, 1, &image); },
      "calibration's size");
}

TEST(SensorModel, TheSameSeedGivesTheSameNoise) {
  RenderOptions o;
  const CameraCalibration c = EurocCam0Calibration();
  const SensorModel sensor(c, o);
  const cv::Mat radiance(c.height, c.width, CV_32F, cv::Scalar(120.0f));
  cv::Mat a, b, other;
  sensor.Expose(radiance, 1.0, 5, &a);
  sensor.Expose(radiance, 1.0, 5, &b);
  sensor.Expose(radiance, 1.0, 6, &other);
  EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0.0);
  EXPECT_GT(cv::norm(a, other, cv::NORM_INF), 0.0);
}

// A 14 x 12 x 4 m room with flat textures of different greys.
TexturedScene FlatRoom() {
  TexturedScene scene;
  scene.geometry = MakeRoomScene(SceneLayout());
  scene.texels_per_m = 16.0;
  std::vector<cv::Mat> crops;
  for (int i = 0; i < 4; ++i) {
    cv::Mat crop(32, 32, CV_8U);
    cv::randu(crop, 0, 255);
    crops.push_back(crop);
  }
  RenderOptions o;
  o.texels_per_m = 16.0;
  return MakeTexturedScene(scene.geometry, crops, o, 3);
}

Eigen::Isometry3d Turning(int64_t t_ns, double rate_rad_s) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() =
      Eigen::AngleAxisd(rate_rad_s * t_ns * 1e-9, Eigen::Vector3d::UnitX())
          .toRotationMatrix();
  T.translation() = Eigen::Vector3d(0.0, 0.0, 1.5);
  return T;
}

TEST(SequenceRenderer, BlurRendersGrowWithTheMotionDuringTheExposure) {
  const TexturedScene scene = FlatRoom();
  RenderOptions o = Plain();
  o.exposure_time_s = 0.01;
  o.blur_step_px = 1.0;
  o.max_blur_samples = 12;
  const CameraCalibration c = EurocCam0Calibration();
  SequenceRenderer renderer({c}, &scene, o, 0.0, 1);
  RenderedFrame frame;
  // Turning about the body x axis (the camera's optical axis is body z):
  // 0.01 s at w rad/s moves the image by about w * 0.01 * 460 px.
  renderer.Render(
      0, [](int64_t t) { return Turning(t, 0.0); }, &frame);
  EXPECT_EQ(frame.blur_samples, 1);
  renderer.Render(
      50000000, [](int64_t t) { return Turning(t, 0.5); }, &frame);
  EXPECT_GE(frame.blur_samples, 2);
  EXPECT_LE(frame.blur_samples, 4);
  renderer.Render(
      100000000, [](int64_t t) { return Turning(t, 10.0); }, &frame);
  EXPECT_EQ(frame.blur_samples, 12);  // capped
  EXPECT_EQ(renderer.stats().frames, 3);
  EXPECT_EQ(renderer.stats().max_blur_samples, 12);
}

TEST(SequenceRenderer, TruthIsThePoseAtTheExposureCentreOnTheImuClock) {
  const TexturedScene scene = FlatRoom();
  const RenderOptions o = Plain();
  const double t_d = 0.005;
  SequenceRenderer renderer({EurocCam0Calibration()}, &scene, o, t_d, 1);
  RenderedFrame frame;
  renderer.Render(
      1000000000, [](int64_t t) { return Turning(t, 0.3); }, &frame);
  EXPECT_EQ(frame.t_ns, 1000000000);
  EXPECT_TRUE(frame.T_w_b.isApprox(Turning(1005000000, 0.3), 1e-12));
  ASSERT_EQ(frame.images.size(), 1u);
  EXPECT_EQ(frame.images[0].type(), CV_8UC1);
}

TEST(SequenceRenderer, GainWalksWithinItsBoundsAndCam1HasItsRatio) {
  const TexturedScene scene = FlatRoom();
  RenderOptions o = Plain();
  o.exposure_time_s = 0.0;
  o.gain_change_per_frame = 0.3;  // large steps: the bounds are reached
  o.min_gain = 0.8;
  o.max_gain = 1.25;
  o.cam1_gain_ratio = 0.5;
  const CameraCalibration c0 = EurocCam0Calibration();
  SequenceRenderer renderer({c0, EurocCam1Calibration()}, &scene, o, 0.0, 1);
  RenderedFrame frame;
  double lo = 1.0, hi = 1.0;
  for (int k = 0; k < 16; ++k) {
    renderer.Render(
        k * 50000000LL, [](int64_t) { return Turning(0, 0.0); }, &frame);
    lo = std::min(lo, frame.gain);
    hi = std::max(hi, frame.gain);
    // Both cameras see the same greys; cam1's mean is about half.
    ASSERT_EQ(frame.images.size(), 2u);
    const double ratio =
        cv::mean(frame.images[1])[0] / cv::mean(frame.images[0])[0];
    EXPECT_NEAR(ratio, 0.5, 0.05);
  }
  EXPECT_GE(lo, 0.8 - 1e-12);
  EXPECT_LE(hi, 1.25 + 1e-12);
  EXPECT_LT(lo, 0.9);
  EXPECT_GT(hi, 1.15);
}

}  // namespace
}  // namespace vio
