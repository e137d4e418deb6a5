#include "render/camera_renderer.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "render/polygon.h"

namespace vio {
namespace {

constexpr double kNearM = 0.01;      // near clipping plane [m]
constexpr double kMaxTangent = 5.7;  // tan(80 deg): widest pinhole view
constexpr int kMarginPx = 2;         // around the view, for interpolation
constexpr int kFillShift = 8;        // sub-pixel bits of cv::fillConvexPoly

Eigen::Matrix3d Intrinsics(const PinholeView& v) {
  Eigen::Matrix3d K;
  K << v.fx, 0.0, v.cx, 0.0, v.fy, v.cy, 0.0, 0.0, 1.0;
  return K;
}

// The undistorted normalised coordinate of a distorted pixel, or throws.
Eigen::Vector2d Undistorted(const CameraModel& camera, double u, double v) {
  Eigen::Vector2d xy;
  if (!camera.PixelToNormalized({u, v}, &xy) ||
      xy.cwiseAbs().maxCoeff() > kMaxTangent) {
    throw std::invalid_argument(
        "camera: pixel (" + std::to_string(u) + ", " + std::to_string(v) +
        ") cannot be undistorted within 80 degrees of the optical axis; the "
        "renderer's pinhole view cannot hold it");
  }
  return xy;
}

// The pinhole view that holds every pixel of the distorted image: the
// camera's focal lengths times `scale`, and a size covering the undistorted
// image border (and a grid inside it) plus a margin.
PinholeView CoveringView(const CameraModel& camera, double scale) {
  const CameraCalibration& c = camera.calibration();
  Eigen::Vector2d lo(1e9, 1e9), hi(-1e9, -1e9);
  auto extend = [&](double u, double v) {
    const Eigen::Vector2d xy = Undistorted(camera, u, v);
    lo = lo.cwiseMin(xy);
    hi = hi.cwiseMax(xy);
  };
  const double right = c.width - 0.5, bottom = c.height - 0.5;
  for (int i = 0; i <= c.width; ++i) {
    extend(i - 0.5, -0.5);
    extend(i - 0.5, bottom);
  }
  for (int j = 0; j <= c.height; ++j) {
    extend(-0.5, j - 0.5);
    extend(right, j - 0.5);
  }
  for (int j = 0; j < c.height; j += 16) {
    for (int i = 0; i < c.width; i += 16) extend(i, j);
  }
  PinholeView view;
  view.fx = c.fx * scale;
  view.fy = c.fy * scale;
  view.cx = -lo.x() * view.fx + kMarginPx;
  view.cy = -lo.y() * view.fy + kMarginPx;
  view.width = static_cast<int>(std::ceil((hi.x() - lo.x()) * view.fx)) +
               2 * kMarginPx + 1;
  view.height = static_cast<int>(std::ceil((hi.y() - lo.y()) * view.fy)) +
                2 * kMarginPx + 1;
  return view;
}

// The plane's corners in the camera frame, clipped to z >= kNearM.
Polygon CameraPolygon(const ScenePlane& p, const Eigen::Isometry3d& T_c_w) {
  const Polygon corners = {
      T_c_w * p.origin_w, T_c_w * (p.origin_w + p.size_u_m * p.axis_u_w),
      T_c_w * (p.origin_w + p.size_u_m * p.axis_u_w + p.size_v_m * p.axis_v_w),
      T_c_w * (p.origin_w + p.size_v_m * p.axis_v_w)};
  return ClipPolygon(corners, Eigen::Vector4d(0.0, 0.0, 1.0, -kNearM));
}

// Projects to the view, as (u, v, 1), and clips to the view's pixels.
Polygon ViewPolygon(const Polygon& camera_polygon, const PinholeView& view) {
  Polygon poly;
  for (const Eigen::Vector3d& p : camera_polygon) {
    poly.emplace_back(view.fx * p.x() / p.z() + view.cx,
                      view.fy * p.y() / p.z() + view.cy, 1.0);
  }
  const double right = view.width - 0.5, bottom = view.height - 0.5;
  poly = ClipPolygon(poly, Eigen::Vector4d(1.0, 0.0, 0.5, 0.0));
  poly = ClipPolygon(poly, Eigen::Vector4d(-1.0, 0.0, right, 0.0));
  poly = ClipPolygon(poly, Eigen::Vector4d(0.0, 1.0, 0.5, 0.0));
  return ClipPolygon(poly, Eigen::Vector4d(0.0, -1.0, bottom, 0.0));
}

// The integer pixel rectangle covering the polygon, inside the view.
cv::Rect Bounds(const Polygon& poly, const PinholeView& view) {
  double u0 = 1e18, v0 = 1e18, u1 = -1e18, v1 = -1e18;
  for (const Eigen::Vector3d& p : poly) {
    u0 = std::min(u0, p.x());
    u1 = std::max(u1, p.x());
    v0 = std::min(v0, p.y());
    v1 = std::max(v1, p.y());
  }
  const int x0 = std::max(0, static_cast<int>(std::floor(u0)));
  const int y0 = std::max(0, static_cast<int>(std::floor(v0)));
  const int x1 = std::min(view.width - 1, static_cast<int>(std::ceil(u1)));
  const int y1 = std::min(view.height - 1, static_cast<int>(std::ceil(v1)));
  return cv::Rect(x0, y0, std::max(0, x1 - x0 + 1), std::max(0, y1 - y0 + 1));
}

// Fills `mask` (the ROI's size) with 255 inside the polygon and 0 outside.
void PolygonMask(const Polygon& poly, const cv::Rect& roi, cv::Mat* mask) {
  mask->setTo(0);
  std::vector<cv::Point> points;
  constexpr double kScale = 1 << kFillShift;
  for (const Eigen::Vector3d& p : poly) {
    points.emplace_back(
        static_cast<int>(std::lround((p.x() - roi.x) * kScale)),
        static_cast<int>(std::lround((p.y() - roi.y) * kScale)));
  }
  cv::fillConvexPoly(*mask, points, cv::Scalar(255), cv::LINE_8, kFillShift);
}

// Shoelace area of a polygon of (u, v, 1) points [px^2].
double Area(const Polygon& poly) {
  double twice = 0.0;
  for (size_t i = 0; i < poly.size(); ++i) {
    const Eigen::Vector3d& a = poly[i];
    const Eigen::Vector3d& b = poly[(i + 1) % poly.size()];
    twice += a.x() * b.y() - b.x() * a.y();
  }
  return 0.5 * std::abs(twice);
}

cv::Mat ToCv(const Eigen::Matrix3d& m) {
  cv::Mat out(3, 3, CV_64F);
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) out.at<double>(r, c) = m(r, c);
  }
  return out;
}

}  // namespace

CameraRenderer::CameraRenderer(const CameraCalibration& calibration,
                               const TexturedScene* scene, double view_scale,
                               double mip_bias)
    : camera_(calibration), scene_(scene), mip_bias_(mip_bias) {
  if (!(view_scale > 0.0 && view_scale <= 4.0)) {
    throw std::invalid_argument("CameraRenderer: view_scale must be in (0, 4]");
  }
  pinhole_ = CoveringView(camera_, view_scale);
  const CameraCalibration& c = calibration;
  map_x_.create(c.height, c.width, CV_32F);
  map_y_.create(c.height, c.width, CV_32F);
  for (int v = 0; v < c.height; ++v) {
    for (int u = 0; u < c.width; ++u) {
      const Eigen::Vector2d xy = Undistorted(camera_, u, v);
      map_x_.at<float>(v, u) =
          static_cast<float>(pinhole_.fx * xy.x() + pinhole_.cx);
      map_y_.at<float>(v, u) =
          static_cast<float>(pinhole_.fy * xy.y() + pinhole_.cy);
    }
  }
  cv::convertMaps(map_x_, map_y_, map_fixed_, map_fraction_, CV_16SC2);
  const cv::Size view(pinhole_.width, pinhole_.height);
  scratch_.warped.create(view, CV_8U);
  scratch_.mask.create(view, CV_8U);
  scratch_.nearer.create(view, CV_8U);
  scratch_.w.create(view, CV_32F);
  ramp_u_.create(pinhole_.height, pinhole_.width, CV_32F);
  ramp_v_.create(pinhole_.height, pinhole_.width, CV_32F);
  for (int v = 0; v < pinhole_.height; ++v) {
    for (int u = 0; u < pinhole_.width; ++u) {
      ramp_u_.at<float>(v, u) = static_cast<float>(u);
      ramp_v_.at<float>(v, u) = static_cast<float>(v);
    }
  }
}

void CameraRenderer::DrawPlane(size_t index, const Eigen::Isometry3d& T_c_w,
                               cv::Mat* image, cv::Mat* inverse_depth,
                               bool depth_test) const {
  const ScenePlane& plane = scene_->geometry.planes()[index];
  const PlaneTexture& texture = scene_->textures[index];
  const Eigen::Vector3d eye_w = T_c_w.inverse().translation();
  if (plane.Normal().dot(eye_w - plane.origin_w) <= 0.0) return;  // its back
  const Polygon view_poly = ViewPolygon(CameraPolygon(plane, T_c_w), pinhole_);
  if (view_poly.size() < 3) return;

  // H: level-0 texel (s, t, 1) -> view pixel, G = H^-1 (header).
  const double rho = scene_->texels_per_m;
  const Eigen::Matrix3d R = T_c_w.linear();
  Eigen::Matrix3d A;
  A.col(0) = R * plane.axis_u_w / rho;
  A.col(1) = R * plane.axis_v_w / rho;
  A.col(2) = T_c_w *
             (plane.origin_w + (0.5 / rho) * (plane.axis_u_w + plane.axis_v_w));
  PlaneWarp warp;
  warp.H = Intrinsics(pinhole_) * A;
  const Eigen::Matrix3d G = warp.H.inverse();
  warp.g2 = G.row(2).transpose();  // w = g2 . (u, v, 1) = 1/z
  const double det_g = std::abs(G.determinant());

  // Level l covers log2(m) + bias in [l - 0.5, l + 0.5); m = sqrt(det_g /
  // w^3), so its lower edge (in m) is the line w = (det_g / m^2)^(1/3).
  const int top = static_cast<int>(texture.levels.size()) - 1;
  auto boundary_w = [&](int level) {  // between level - 1 and level
    const double m = std::exp2(level - 0.5 - mip_bias_);
    return std::cbrt(det_g / (m * m));
  };
  double w_min = 1e300, w_max = -1e300;
  for (const Eigen::Vector3d& p : view_poly) {
    w_min = std::min(w_min, warp.g2.dot(p));
    w_max = std::max(w_max, warp.g2.dot(p));
  }
  const Eigen::Vector3d& g2 = warp.g2;
  for (int level = 0; level <= top; ++level) {
    Polygon band = view_poly;
    if (level > 0) {  // w <= boundary_w(level)
      const double w_hi = boundary_w(level);
      if (w_min > w_hi) continue;
      band = ClipPolygon(band,
                         Eigen::Vector4d(-g2.x(), -g2.y(), w_hi - g2.z(), 0.0));
    }
    if (level < top) {  // w > boundary_w(level + 1)
      const double w_lo = boundary_w(level + 1);
      if (w_max <= w_lo) continue;
      band = ClipPolygon(band,
                         Eigen::Vector4d(g2.x(), g2.y(), g2.z() - w_lo, 0.0));
    }
    warp.texture = &texture.levels[level];
    warp.scale = std::exp2(level);
    DrawPolygon(band, warp, image, inverse_depth, depth_test, 0);
  }
}

void CameraRenderer::DrawPolygon(const Polygon& poly, const PlaneWarp& warp,
                                 cv::Mat* image, cv::Mat* inverse_depth,
                                 bool depth_test, int depth) const {
  if (poly.size() < 3) return;
  const cv::Rect roi = Bounds(poly, pinhole_);
  if (roi.empty()) return;
  // A warp costs its whole rectangle: cut a polygon that fills little of a
  // large one in two along the longer side.
  constexpr int kMaxSplits = 6;
  constexpr double kMinFill = 0.6;
  constexpr int kMinSplitArea = 64 * 64;  // [px]
  if (depth < kMaxSplits && roi.area() > kMinSplitArea &&
      Area(poly) < kMinFill * roi.area()) {
    const bool vertical_cut = roi.width >= roi.height;
    const double mid =
        vertical_cut ? roi.x + 0.5 * roi.width : roi.y + 0.5 * roi.height;
    const Eigen::Vector4d k = vertical_cut ? Eigen::Vector4d(1, 0, -mid, 0)
                                           : Eigen::Vector4d(0, 1, -mid, 0);
    DrawPolygon(ClipPolygon(poly, k), warp, image, inverse_depth, depth_test,
                depth + 1);
    DrawPolygon(ClipPolygon(poly, -k), warp, image, inverse_depth, depth_test,
                depth + 1);
    return;
  }
  // Level-l texel s_l is level-0 texel 2^l s_l; then shift to the ROI.
  Eigen::Matrix3d M =
      warp.H * Eigen::Vector3d(warp.scale, warp.scale, 1.0).asDiagonal();
  M.row(0) -= roi.x * M.row(2);
  M.row(1) -= roi.y * M.row(2);
  // Views into the view-sized scratch buffers: no allocation per polygon.
  cv::Mat warped = scratch_.warped(roi);
  cv::warpPerspective(*warp.texture, warped, ToCv(M), roi.size(),
                      cv::INTER_LINEAR, cv::BORDER_REPLICATE);
  cv::Mat mask = scratch_.mask(roi);
  PolygonMask(poly, roi, &mask);
  if (depth_test || inverse_depth) {
    cv::Mat w = scratch_.w(roi);  // inverse depth over the ROI
    cv::addWeighted(ramp_u_(roi), warp.g2.x(), ramp_v_(roi), warp.g2.y(),
                    warp.g2.z(), w);
    cv::Mat* buffer = inverse_depth ? inverse_depth : &scratch_.depth;
    if (depth_test) {
      cv::Mat nearer = scratch_.nearer(roi);
      cv::compare(w, (*buffer)(roi), nearer, cv::CMP_GT);
      cv::bitwise_and(mask, nearer, mask);
    }
    w.copyTo((*buffer)(roi), mask);
  }
  warped.copyTo((*image)(roi), mask);
}

void CameraRenderer::RenderPinhole(const Eigen::Isometry3d& T_w_c,
                                   cv::Mat* image,
                                   cv::Mat* inverse_depth) const {
  image->create(pinhole_.height, pinhole_.width, CV_8U);
  image->setTo(0);
  cv::Mat* depth = inverse_depth ? inverse_depth : &scratch_.depth;
  depth->create(pinhole_.height, pinhole_.width, CV_32F);
  depth->setTo(0.0f);
  const Eigen::Isometry3d T_c_w = T_w_c.inverse();
  // The enclosing planes never overlap and lie behind the rest: no depth
  // test for them, and their depth is written only when asked for.
  const size_t enclosing = scene_->geometry.num_enclosing();
  for (size_t i = 0; i < scene_->geometry.planes().size(); ++i) {
    DrawPlane(i, T_c_w, image, inverse_depth, i >= enclosing);
  }
}

void CameraRenderer::RenderRadiance(const std::vector<Eigen::Isometry3d>& T_w_c,
                                    cv::Mat* radiance) const {
  if (T_w_c.empty()) {
    throw std::invalid_argument("RenderRadiance: no camera pose");
  }
  if (T_w_c.size() == 1) {
    RenderPinhole(T_w_c[0], &scratch_.view);
    cv::remap(scratch_.view, scratch_.distorted, map_fixed_, map_fraction_,
              cv::INTER_LINEAR, cv::BORDER_CONSTANT, cv::Scalar(0));
    scratch_.distorted.convertTo(*radiance, CV_32F);
    return;
  }
  scratch_.sum.create(pinhole_.height, pinhole_.width, CV_32F);
  scratch_.sum.setTo(0.0f);
  for (const Eigen::Isometry3d& pose : T_w_c) {
    RenderPinhole(pose, &scratch_.view);
    cv::accumulate(scratch_.view, scratch_.sum);
  }
  scratch_.sum *= 1.0 / static_cast<double>(T_w_c.size());
  cv::remap(scratch_.sum, *radiance, map_fixed_, map_fraction_,
            cv::INTER_LINEAR, cv::BORDER_CONSTANT, cv::Scalar(0));
}

cv::Mat CameraRenderer::RenderInverseDepth(
    const Eigen::Isometry3d& T_w_c) const {
  cv::Mat view, depth, out;
  RenderPinhole(T_w_c, &view, &depth);
  cv::remap(depth, out, map_x_, map_y_, cv::INTER_NEAREST, cv::BORDER_CONSTANT,
            cv::Scalar(0));
  return out;
}

}  // namespace vio
