#ifndef VIO_FRONTEND_CORNER_DETECTOR_H_
#define VIO_FRONTEND_CORNER_DETECTOR_H_

// Shi-Tomasi corners (the smaller eigenvalue of the 3 x 3 gradient
// covariance, cv::cornerMinEigenVal) where a mask allows them, with the
// selection rule of cv::goodFeaturesToTrack:
//   1. a candidate is a pixel of the mask, not on the image's outer row or
//      column, whose response is above quality x the largest response
//      inside the mask and is the largest of its 3 x 3 neighbourhood;
//   2. candidates are taken strongest first (equal responses: the later
//      pixel in row-major order first), each kept when it is at least
//      min_distance from every corner kept before it, until max_corners.
//
// Why not cv::goodFeaturesToTrack itself: it computes the response over the
// whole image, and the tracker's mask (a disc of min_distance around every
// live track) usually leaves only a few gaps open. That was a quarter of the
// stereo replay's CPU time (docs/speed.md). Here the response is computed,
// with cv::cornerMinEigenVal on sub-images, only on the tiles of the image
// that hold an open mask pixel (plus the ring of neighbours that the local
// maximum test reads). OpenCV's box filter sums rows with a running sum that
// starts at the top of whatever it is given, so a response computed on a
// tile can differ from the whole image's in the last bits of a float; the
// corners found are otherwise the same.

#include <opencv2/core.hpp>
#include <vector>

namespace vio {

class CornerDetector {
 public:
  // `tile_px`: side of the square tiles the image is split into for the
  // response [px], > 0.
  explicit CornerDetector(int tile_px = 16);

  // Up to max_corners corners of `image` (8-bit grey) at pixels where
  // `mask` (8-bit, the image's size) is non-zero, strongest first. Throws
  // std::invalid_argument on an image or mask of the wrong type or size.
  std::vector<cv::Point2f> Detect(const cv::Mat& image, const cv::Mat& mask,
                                  int max_corners, double quality,
                                  double min_distance);

  // The share of the image's pixels whose response the last Detect
  // computed, in [0, 1] (margins included).
  double computed_share() const { return computed_share_; }

 private:
  int tile_px_;
  cv::Mat response_;  // the minimum eigenvalue, 0 where not computed
  cv::Mat tile_response_;
  double computed_share_ = 0.0;
};

}  // namespace vio

#endif  // VIO_FRONTEND_CORNER_DETECTOR_H_
