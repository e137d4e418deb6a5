#include "geometry/camera_model.h"

#include <gtest/gtest.h>

namespace vio {
namespace {

// EuRoC V1_01 cam0 (radtan, the default calibration) and a fisheye camera
// with the coefficients of a typical Kalibr equidistant calibration.
CameraCalibration RadTan() { return CameraCalibration(); }

CameraCalibration Equidistant() {
  CameraCalibration c;
  c.distortion = DistortionModel::kEquidistant;
  c.fx = 190.98;
  c.fy = 190.97;
  c.cx = 254.93;
  c.cy = 256.90;
  c.width = 512;
  c.height = 512;
  c.distortion_coefficients << 0.00348, 0.00072, -0.00205, 0.00020;
  return c;
}

class CameraModelTest : public ::testing::TestWithParam<CameraCalibration> {};

// distort(undistort(uv)) == uv over a grid covering the whole image. A
// fisheye image's corners lie outside its field of view (a distorted angle
// th_d beyond ~90 deg has no undistorted point), so for the equidistant model
// the grid covers the pixels up to th_d = 80 deg.
TEST_P(CameraModelTest, UndistortRoundTripOverTheImage) {
  const CameraModel camera(GetParam());
  const auto& c = camera.calibration();
  const double max_th_d = 80.0 * M_PI / 180.0;
  double worst = 0.0;
  int checked = 0;
  for (int v = 0; v <= c.height; v += 8) {
    for (int u = 0; u <= c.width; u += 8) {
      const Eigen::Vector2d uv(u, v);
      const Eigen::Vector2d xy_d((u - c.cx) / c.fx, (v - c.cy) / c.fy);
      if (c.distortion == DistortionModel::kEquidistant &&
          xy_d.norm() > max_th_d) {
        continue;
      }
      ++checked;
      Eigen::Vector2d xy;
      ASSERT_TRUE(camera.PixelToNormalized(uv, &xy)) << u << ", " << v;
      worst = std::max(worst, (camera.NormalizedToPixel(xy) - uv).norm());
    }
  }
  EXPECT_LT(worst, 1e-6);
  EXPECT_GT(checked, 2000);
}

TEST_P(CameraModelTest, DistortionJacobianMatchesNumericDiff) {
  const CameraModel camera(GetParam());
  const double h = 1e-7;
  for (double x : {-0.6, -0.1, 0.0, 1e-12, 0.3, 0.7}) {
    for (double y : {-0.5, 0.0, 0.2, 0.45}) {
      const Eigen::Vector2d xy(x, y);
      Eigen::Matrix2d J;
      camera.Distort(xy, &J);
      Eigen::Matrix2d numeric;
      for (int k = 0; k < 2; ++k) {
        const Eigen::Vector2d d = h * Eigen::Vector2d::Unit(k);
        numeric.col(k) =
            (camera.Distort(xy + d) - camera.Distort(xy - d)) / (2.0 * h);
      }
      EXPECT_LT((J - numeric).cwiseAbs().maxCoeff(), 1e-7)
          << "at " << x << ", " << y;
    }
  }
}

TEST_P(CameraModelTest, ProjectRejectsPointsBehindTheCamera) {
  const CameraModel camera(GetParam());
  Eigen::Vector2d uv;
  EXPECT_FALSE(camera.Project({0.1, 0.2, -1.0}, &uv));
  EXPECT_FALSE(camera.Project({0.0, 0.0, 0.0}, &uv));
  ASSERT_TRUE(camera.Project({0.0, 0.0, 2.0}, &uv));
  EXPECT_NEAR(uv.x(), camera.calibration().cx, 1e-12);
  EXPECT_NEAR(uv.y(), camera.calibration().cy, 1e-12);
}

INSTANTIATE_TEST_SUITE_P(Models, CameraModelTest,
                         ::testing::Values(RadTan(), Equidistant()));

TEST(CameraCalibration, ValidateNamesTheField) {
  CameraCalibration c;
  std::string message;
  EXPECT_TRUE(c.Validate(&message));
  c.fx = -1.0;
  EXPECT_FALSE(c.Validate(&message));
  EXPECT_EQ(message.rfind("intrinsics", 0), 0u) << message;
  c = CameraCalibration();
  c.rate_hz = 0.0;
  EXPECT_FALSE(c.Validate(&message));
  EXPECT_EQ(message.rfind("rate_hz", 0), 0u) << message;
}

TEST(CameraCalibration, ParsesDistortionModelNames) {
  DistortionModel m;
  EXPECT_TRUE(ParseDistortionModel("radial-tangential", &m));
  EXPECT_EQ(m, DistortionModel::kRadialTangential);
  EXPECT_TRUE(ParseDistortionModel("equidistant", &m));
  EXPECT_EQ(m, DistortionModel::kEquidistant);
  EXPECT_FALSE(ParseDistortionModel("kannala", &m));
}

}  // namespace
}  // namespace vio
