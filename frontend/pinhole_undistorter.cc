#include "frontend/pinhole_undistorter.h"

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <string>

namespace vio {
namespace {

void MakeMaps(DistortionModel model, const cv::Matx33d& K, const cv::Vec4d& d,
              const cv::Matx33d& K_new, const cv::Size& size, cv::Mat* map_u,
              cv::Mat* map_v) {
  if (model == DistortionModel::kEquidistant) {
    cv::fisheye::initUndistortRectifyMap(K, d, cv::Matx33d::eye(), K_new, size,
                                         CV_32FC1, *map_u, *map_v);
  } else {
    cv::initUndistortRectifyMap(K, d, cv::Matx33d::eye(), K_new, size, CV_32FC1,
                                *map_u, *map_v);
  }
}

// True when every undistorted pixel reads from inside the raw image.
bool AllInside(const cv::Mat& map_u, const cv::Mat& map_v,
               const cv::Size& size) {
  double u_min, u_max, v_min, v_max;
  cv::minMaxLoc(map_u, &u_min, &u_max);
  cv::minMaxLoc(map_v, &v_min, &v_max);
  return u_min >= 0.0 && v_min >= 0.0 && u_max <= size.width - 1 &&
         v_max <= size.height - 1;
}

}  // namespace

PinholeUndistorter::PinholeUndistorter(const CameraCalibration& c)
    : width_(c.width), height_(c.height) {
  std::string message;
  if (!c.Validate(&message)) {
    throw std::invalid_argument("PinholeUndistorter: " + message);
  }
  const cv::Matx33d K(c.fx, 0.0, c.cx, 0.0, c.fy, c.cy, 0.0, 0.0, 1.0);
  const cv::Vec4d d(c.distortion_coefficients[0], c.distortion_coefficients[1],
                    c.distortion_coefficients[2], c.distortion_coefficients[3]);
  const cv::Size size(c.width, c.height);
  if (c.distortion == DistortionModel::kNone) {
    pinhole_ = {c.fx, c.fy, c.cx, c.cy};
    return;
  }
  // The calibration's own K first: it keeps the resolution at the centre.
  // Under barrel distortion (EuRoC's k1 < 0) every undistorted pixel then
  // maps inside the raw image; if one does not, fall back to OpenCV's
  // optimal K with alpha = 0 (the widest view with all pixels valid).
  cv::Matx33d K_new = K;
  MakeMaps(c.distortion, K, d, K_new, size, &map_u_, &map_v_);
  if (!AllInside(map_u_, map_v_, size)) {
    if (c.distortion == DistortionModel::kEquidistant) {
      cv::fisheye::estimateNewCameraMatrixForUndistortRectify(
          K, d, size, cv::Matx33d::eye(), K_new, 0.0);
    } else {
      K_new = cv::getOptimalNewCameraMatrix(K, d, size, 0.0, size);
    }
    MakeMaps(c.distortion, K, d, K_new, size, &map_u_, &map_v_);
  }
  pinhole_ = {K_new(0, 0), K_new(1, 1), K_new(0, 2), K_new(1, 2)};
}

cv::Mat PinholeUndistorter::Undistort(const cv::Mat& raw) const {
  if (raw.empty() || raw.type() != CV_8UC1 || raw.cols != width_ ||
      raw.rows != height_) {
    throw std::invalid_argument(
        "PinholeUndistorter::Undistort: expected an 8-bit grey image of " +
        std::to_string(width_) + "x" + std::to_string(height_) + " (got " +
        std::to_string(raw.cols) + "x" + std::to_string(raw.rows) + ", type " +
        std::to_string(raw.type()) + ")");
  }
  cv::Mat grey;
  raw.convertTo(grey, CV_32F);
  if (map_u_.empty()) return grey;
  cv::Mat out;
  cv::remap(grey, out, map_u_, map_v_, cv::INTER_LINEAR, cv::BORDER_REPLICATE);
  return out;
}

}  // namespace vio
