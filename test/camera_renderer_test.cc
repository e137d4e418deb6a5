// The renderer's geometry against exact truth: dots painted at known places
// of a wall must appear where the camera model projects them (through the
// pinhole view, the mip levels and the distortion remap), and the depth
// buffer must agree with ray casting, box in front of the wall included.

#include "render/camera_renderer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <random>

#include "dataset/simulator.h"
#include "render/scene.h"
#include "test/testing/expect_error.h"

namespace vio {
namespace {

constexpr double kTexelsPerM = 64.0;
constexpr int kDotSpacing = 32;       // [texels]
constexpr double kDotSigma = 2.0;     // [texels]
constexpr float kBackground = 40.0f;  // [grey levels]

// A flat grey texture for every plane, with its mip levels.
PlaneTexture Flat(const ScenePlane& p, uchar grey) {
  PlaneTexture t;
  t.levels.push_back(cv::Mat(static_cast<int>(p.size_v_m * kTexelsPerM),
                             static_cast<int>(p.size_u_m * kTexelsPerM), CV_8U,
                             cv::Scalar(grey)));
  return t;
}

// Gaussian dots every kDotSpacing texels (the first at texel 16, 16), and
// the mip levels by cv::pyrDown as the texture atlas makes them.
PlaneTexture Dots(const ScenePlane& p) {
  const int cols = static_cast<int>(p.size_u_m * kTexelsPerM);
  const int rows = static_cast<int>(p.size_v_m * kTexelsPerM);
  cv::Mat level0(rows, cols, CV_8U);
  for (int t = 0; t < rows; ++t) {
    for (int s = 0; s < cols; ++s) {
      const double ds = (s % kDotSpacing) - kDotSpacing / 2;
      const double dt = (t % kDotSpacing) - kDotSpacing / 2;
      level0.at<uchar>(t, s) = cv::saturate_cast<uchar>(
          kBackground +
          180.0 * std::exp(-(ds * ds + dt * dt) / (2 * kDotSigma * kDotSigma)));
    }
  }
  PlaneTexture texture;
  texture.levels.push_back(level0);
  while (texture.levels.back().cols >= 16 && texture.levels.back().rows >= 16) {
    cv::Mat next;
    cv::pyrDown(texture.levels.back(), next);
    texture.levels.push_back(next);
  }
  return texture;
}

// The default room; plane `dotted` carries the dots, the others are flat.
TexturedScene DottedRoom(int dotted, const std::vector<SceneBox>& boxes = {}) {
  SceneLayout layout;
  layout.boxes = boxes;
  TexturedScene scene;
  scene.geometry = MakeRoomScene(layout);
  scene.texels_per_m = kTexelsPerM;
  for (size_t i = 0; i < scene.geometry.planes().size(); ++i) {
    const ScenePlane& p = scene.geometry.planes()[i];
    scene.textures.push_back(static_cast<int>(i) == dotted
                                 ? Dots(p)
                                 : Flat(p, static_cast<uchar>(60 + 10 * i)));
  }
  return scene;
}

// A camera at `eye` looking along +x (image right = -y, down = -z), turned
// by `yaw` about the vertical.
Eigen::Isometry3d LookingAlongX(const Eigen::Vector3d& eye, double yaw) {
  Eigen::Matrix3d R;
  R.col(0) = Eigen::Vector3d(0, -1, 0);
  R.col(1) = Eigen::Vector3d(0, 0, -1);
  R.col(2) = Eigen::Vector3d(1, 0, 0);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * R;
  T.translation() = eye;
  return T;
}

// Intensity-weighted centroid of (intensity - background) over a square
// window around `guess`; intensity(u, v) gives a pixel's grey level.
template <typename Intensity>
Eigen::Vector2d Centroid(const Intensity& intensity,
                         const Eigen::Vector2d& guess, int radius) {
  const int u0 = static_cast<int>(std::lround(guess.x()));
  const int v0 = static_cast<int>(std::lround(guess.y()));
  double sum = 0.0, su = 0.0, sv = 0.0;
  for (int v = v0 - radius; v <= v0 + radius; ++v) {
    for (int u = u0 - radius; u <= u0 + radius; ++u) {
      const double w = std::max(0.0, intensity(u, v) - kBackground);
      sum += w;
      su += w * u;
      sv += w * v;
    }
  }
  return {su / sum, sv / sum};
}

// The camera of the renderer's undistorted pinhole view.
CameraCalibration PinholeOf(const PinholeView& view) {
  CameraCalibration c;
  c.width = view.width;
  c.height = view.height;
  c.fx = view.fx;
  c.fy = view.fy;
  c.cx = view.cx;
  c.cy = view.cy;
  c.distortion = DistortionModel::kNone;
  return c;
}

// Median and largest distance between each dot's centroid in the rendered
// pinhole view (the warps and mip levels, without the distortion) and its
// centroid in the exact image of the dot, made by casting every pixel's ray
// onto the wall and evaluating the continuous Gaussian there (so the
// perspective's own shift of an oblique blob's centroid cancels), over the
// dots inside `max_radius_px` of the principal point.
void DotErrors(const Eigen::Isometry3d& T_w_c, int window_px,
               double max_radius_px, double* median, double* worst,
               int* count) {
  const TexturedScene scene = DottedRoom(3);  // the wall x = +7, n = -x
  const CameraRenderer renderer(EurocCam0Calibration(), &scene);
  cv::Mat view, radiance;
  renderer.RenderPinhole(T_w_c, &view);
  view.convertTo(radiance, CV_32F);
  const CameraCalibration calibration = PinholeOf(renderer.pinhole());
  const CameraModel camera(calibration);
  const ScenePlane& wall = scene.geometry.planes()[3];
  std::vector<double> errors;
  for (int t = kDotSpacing / 2; t < wall.size_v_m * kTexelsPerM;
       t += kDotSpacing) {
    for (int s = kDotSpacing / 2; s < wall.size_u_m * kTexelsPerM;
         s += kDotSpacing) {
      // Texel (s, t) shows the plane point ((s + 0.5), (t + 0.5)) / rho.
      const Eigen::Vector3d X = wall.origin_w +
                                (s + 0.5) / kTexelsPerM * wall.axis_u_w +
                                (t + 0.5) / kTexelsPerM * wall.axis_v_w;
      Eigen::Vector2d uv;
      if (!camera.Project(T_w_c.inverse() * X, &uv)) continue;
      const Eigen::Vector2d centre(calibration.cx, calibration.cy);
      if ((uv - centre).norm() > max_radius_px || uv.x() < window_px + 2 ||
          uv.y() < window_px + 2 ||
          uv.x() > calibration.width - window_px - 3 ||
          uv.y() > calibration.height - window_px - 3) {
        continue;
      }
      // The whole window on the wall, and no other dot within it.
      bool clean = true;
      for (int k = 0; k < 4 && clean; ++k) {
        const Eigen::Vector2d corner =
            uv + window_px * Eigen::Vector2d(k % 2 ? 1 : -1, k / 2 ? 1 : -1);
        Eigen::Vector2d xy;
        SceneHit hit;
        clean =
            camera.PixelToNormalized(corner, &xy) &&
            scene.geometry.Intersect(T_w_c.translation(),
                                     T_w_c.linear() * xy.homogeneous(), &hit) &&
            hit.plane == 3;
      }
      for (int k = 0; k < 4 && clean; ++k) {
        const int ds = k == 0 ? kDotSpacing : k == 1 ? -kDotSpacing : 0;
        const int dt = k == 2 ? kDotSpacing : k == 3 ? -kDotSpacing : 0;
        Eigen::Vector2d other;
        clean = !camera.Project(
                    T_w_c.inverse() * (X + ds / kTexelsPerM * wall.axis_u_w +
                                       dt / kTexelsPerM * wall.axis_v_w),
                    &other) ||
                (other - uv).cwiseAbs().maxCoeff() > 2.0 * window_px;
      }
      if (!clean) continue;
      const auto rendered = [&](int u, int v) {
        return static_cast<double>(radiance.at<float>(v, u));
      };
      const auto exact = [&](int u, int v) {
        Eigen::Vector2d xy;
        SceneHit hit;
        camera.PixelToNormalized({u, v}, &xy);
        scene.geometry.Intersect(T_w_c.translation(),
                                 T_w_c.linear() * xy.homogeneous(), &hit);
        const double ds = hit.ab.x() * kTexelsPerM - 0.5 - s;
        const double dt = hit.ab.y() * kTexelsPerM - 0.5 - t;
        return kBackground + 180.0 * std::exp(-(ds * ds + dt * dt) /
                                              (2 * kDotSigma * kDotSigma));
      };
      errors.push_back(
          (Centroid(rendered, uv, window_px) - Centroid(exact, uv, window_px))
              .norm());
    }
  }
  *count = static_cast<int>(errors.size());
  std::sort(errors.begin(), errors.end());
  *median = errors.empty() ? 1e9 : errors[errors.size() / 2];
  *worst = errors.empty() ? 1e9 : errors.back();
}

TEST(CameraRenderer, DotsAppearWhereThePinholeViewProjectsThem) {
  // 2 m from the wall, facing it: a texel is 3.6 pixels (level 0), dots
  // 7 px wide; the view of a parallel plane is a similarity, so a dot's
  // centroid is its centre's projection.
  double median = 0.0, worst = 0.0;
  int count = 0;
  DotErrors(LookingAlongX({5.0, 0.3, 2.1}, 0.0), 30, 400.0, &median, &worst,
            &count);
  EXPECT_GE(count, 20);
  EXPECT_LT(median, 0.02);
  EXPECT_LT(worst, 0.04);
  // Turned by 35 degrees: an oblique wall, several mip levels in the view.
  DotErrors(LookingAlongX({3.0, 0.3, 2.1}, 0.6), 14, 400.0, &median, &worst,
            &count);
  EXPECT_GE(count, 20);
  EXPECT_LT(median, 0.02);
  EXPECT_LT(worst, 0.05);
}

TEST(CameraRenderer, DotsStayPutAtCoarserMipLevels) {
  // 12 m from the wall: 1.7 texels per pixel, level 1.
  double median = 0.0, worst = 0.0;
  int count = 0;
  DotErrors(LookingAlongX({-5.0, 0.3, 2.1}, 0.0), 7, 400.0, &median, &worst,
            &count);
  EXPECT_GE(count, 20);
  EXPECT_LT(median, 0.02);
  EXPECT_LT(worst, 0.05);
}

TEST(CameraRenderer, DistortionAgreesWithOpenCvsOwnModel) {
  // The distorted image undistorted by OpenCV's radial-tangential model
  // (an implementation independent of geometry/camera_model) into the
  // pinhole view's camera must give back the pinhole view.
  const TexturedScene scene = DottedRoom(3);
  const CameraCalibration c = EurocCam0Calibration();
  const CameraRenderer renderer(c, &scene);
  const Eigen::Isometry3d T_w_c = LookingAlongX({5.0, 0.3, 2.1}, 0.2);
  cv::Mat view, distorted;
  renderer.RenderPinhole(T_w_c, &view);
  renderer.RenderRadiance({T_w_c}, &distorted);
  const PinholeView& p = renderer.pinhole();
  const cv::Matx33d K(c.fx, 0, c.cx, 0, c.fy, c.cy, 0, 0, 1);
  const cv::Matx33d K_view(p.fx, 0, p.cx, 0, p.fy, p.cy, 0, 0, 1);
  const Eigen::Vector4d& d = c.distortion_coefficients;
  const cv::Vec4d D(d[0], d[1], d[2], d[3]);
  cv::Mat map_x, map_y, undistorted;
  cv::initUndistortRectifyMap(K, D, cv::Matx33d::eye(), K_view,
                              cv::Size(p.width, p.height), CV_32FC1, map_x,
                              map_y);
  cv::remap(distorted, undistorted, map_x, map_y, cv::INTER_LINEAR);
  // Compare where the distorted image is defined and away from its border.
  cv::Mat reference;
  view.convertTo(reference, CV_32F);
  double sum = 0.0;
  int n = 0;
  for (int v = 0; v < p.height; ++v) {
    for (int u = 0; u < p.width; ++u) {
      const float su = map_x.at<float>(v, u), sv = map_y.at<float>(v, u);
      if (su < 5 || sv < 5 || su > c.width - 6 || sv > c.height - 6) continue;
      sum += std::abs(undistorted.at<float>(v, u) - reference.at<float>(v, u));
      ++n;
    }
  }
  EXPECT_GT(n, 200000);
  // Two interpolations of 7 px wide dots: a fraction of a grey level; a
  // shift of 0.5 px gives about 3.
  EXPECT_LT(sum / n, 0.5);
}

TEST(CameraRenderer, DepthBufferAgreesWithRayCastingAndCoversTheImage) {
  SceneBox box;
  box.center_xy_m = {3.0, 0.0};
  box.size_m = {1.0, 2.0, 1.5};
  const TexturedScene scene = DottedRoom(0, {box});
  const CameraCalibration calibration = EurocCam0Calibration();
  const CameraRenderer renderer(calibration, &scene);
  const CameraModel camera(calibration);
  std::mt19937 rng(42);
  std::uniform_int_distribution<int> u(0, calibration.width - 1);
  std::uniform_int_distribution<int> v(0, calibration.height - 1);
  int on_box = 0, compared = 0;
  for (double yaw : {0.0, 0.8, 2.5}) {
    const Eigen::Isometry3d T_w_c = LookingAlongX({0.0, 0.3, 1.0}, yaw);
    const cv::Mat inverse_depth = renderer.RenderInverseDepth(T_w_c);
    EXPECT_EQ(cv::countNonZero(inverse_depth > 0.0f),
              inverse_depth.rows * inverse_depth.cols)
        << "a pixel saw nothing in a closed room";
    for (int i = 0; i < 300; ++i) {
      const int pu = u(rng), pv = v(rng);
      // Skip pixels next to an edge between planes.
      int planes[2] = {-1, -1};
      bool edge = false;
      double depth = 0.0;
      for (int k = 0; k < 9 && !edge; ++k) {
        Eigen::Vector2d xy;
        ASSERT_TRUE(camera.PixelToNormalized(
            {pu + 2 * (k % 3 - 1), pv + 2 * (k / 3 - 1)}, &xy));
        SceneHit hit;
        ASSERT_TRUE(scene.geometry.Intersect(
            T_w_c.translation(), T_w_c.linear() * xy.homogeneous(), &hit));
        if (k == 0) planes[0] = hit.plane;
        if (hit.plane != planes[0]) edge = true;
        if (k == 4) {
          planes[1] = hit.plane;
          depth = hit.distance / xy.homogeneous().norm();  // z of the point
        }
      }
      if (edge) continue;
      ++compared;
      if (planes[1] >= 6) ++on_box;
      EXPECT_NEAR(1.0 / inverse_depth.at<float>(pv, pu), depth, 0.01 * depth)
          << "pixel " << pu << ", " << pv;
    }
  }
  EXPECT_GT(compared, 600);
  EXPECT_GT(on_box, 20);
}

TEST(CameraRenderer, MotionBlurIsTheMeanOfTheRenders) {
  const TexturedScene scene = DottedRoom(3);
  const CameraRenderer renderer(EurocCam0Calibration(), &scene);
  const Eigen::Isometry3d a = LookingAlongX({4.0, 0.3, 2.0}, 0.0);
  const Eigen::Isometry3d b = LookingAlongX({4.0, 0.35, 2.0}, 0.01);
  cv::Mat ra, rb, blurred, again;
  renderer.RenderRadiance({a}, &ra);
  renderer.RenderRadiance({b}, &rb);
  renderer.RenderRadiance({a, b}, &blurred);
  renderer.RenderRadiance({a, b}, &again);
  // One pose is remapped in 8 bits, the mean in float: rounding only.
  cv::Mat difference = cv::abs(blurred - 0.5 * (ra + rb));
  double worst = 0.0;
  cv::minMaxLoc(difference, nullptr, &worst);
  EXPECT_LT(worst, 1.0);
  EXPECT_GT(cv::norm(ra, rb, cv::NORM_INF), 50.0);         // the two differ
  EXPECT_EQ(cv::norm(blurred, again, cv::NORM_INF), 0.0);  // deterministic
}

TEST(CameraRenderer, RefusesWhatItCannotRender) {
  const TexturedScene scene = DottedRoom(3);
  const CameraRenderer renderer(EurocCam0Calibration(), &scene);
  cv::Mat radiance;
  ExpectErrorContaining<std::invalid_argument>(
      [&] { renderer.RenderRadiance({}, &radiance); }, "no camera pose");
  CameraCalibration fisheye = EurocCam0Calibration();
  fisheye.distortion = DistortionModel::kEquidistant;
  fisheye.distortion_coefficients.setZero();
  fisheye.fx = fisheye.fy = 60.0;  // 150 degrees across
  ExpectErrorContaining<std::invalid_argument>(
      [&] { CameraRenderer wide(fisheye, &scene); }, "within 80 degrees");
}

}  // namespace
}  // namespace vio
