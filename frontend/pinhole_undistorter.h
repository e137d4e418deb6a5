#ifndef VIO_FRONTEND_PINHOLE_UNDISTORTER_H_
#define VIO_FRONTEND_PINHOLE_UNDISTORTER_H_

// Removes a camera's lens distortion once per image, so the direct method
// works on a plain pinhole (geometry/pinhole.h), as LSD-SLAM and DSO do.
// The new pinhole is the calibration's own K when every undistorted pixel then
// reads from inside the raw image (barrel distortion, as EuRoC's), else
// OpenCV's optimal camera matrix with alpha = 0: either way the undistorted
// image has no invalid border. The camera frame is unchanged (no rectifying
// rotation), so the calibration's extrinsics still hold.
// Radial-tangential and equidistant (fisheye) models go through OpenCV's
// matching functions; a camera without distortion passes through.

#include <opencv2/core.hpp>

#include "geometry/camera_model.h"
#include "geometry/pinhole.h"

namespace vio {

class PinholeUndistorter {
 public:
  explicit PinholeUndistorter(const CameraCalibration& calibration);

  // The pinhole of the undistorted images.
  const Pinhole& pinhole() const { return pinhole_; }
  int width() const { return width_; }
  int height() const { return height_; }

  // The undistorted image, 32-bit float grey values (bilinear resampling of
  // the raw 8-bit image). Throws std::invalid_argument unless `raw` is 8-bit
  // single-channel of the calibration's size.
  cv::Mat Undistort(const cv::Mat& raw) const;

 private:
  int width_, height_;
  Pinhole pinhole_;
  cv::Mat map_u_, map_v_;  // CV_32FC1 remap tables (empty: no distortion)
};

}  // namespace vio

#endif  // VIO_FRONTEND_PINHOLE_UNDISTORTER_H_
