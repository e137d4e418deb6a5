#ifndef VIO_FRONTEND_STEREO_MATCHER_H_
#define VIO_FRONTEND_STEREO_MATCHER_H_

// Matches left-image features into the right image of a calibrated stereo
// pair: Lucas-Kanade left -> right from the left position, a reverse check
// (right -> left must return to the start), and the epipolar constraint of
// the calibrated pair.
//
// Epipolar constraint. With the relative pose T_c0_c1 (p_c0 = R_c0_c1 p_c1 +
// t_c0_c1) and undistorted bearings f0 = (x0, y0, 1), f1 = (x1, y1, 1) of one
// point, f0, t and R f1 are coplanar:  f0^T [t]x R f1 = 0, i.e. f1 lies on the
// line l1 = ([t]x R)^T f0 of the right normalised plane. The distance of f1
// to l1, times the right camera's focal length, is the error in pixels.
// A match must also triangulate in front of both cameras.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <opencv2/core.hpp>
#include <vector>

#include "frontend/frontend_options.h"
#include "geometry/camera_model.h"
#include "geometry/feature_observation.h"

namespace vio {

// One image of the pair as the matcher reads it: equalised when
// options.equalize, with its LK pyramid (image levels and their derivatives,
// BuildKltPyramid). Built once per image and used by both directions of the
// match (left -> right and the reverse check), which calcOpticalFlowPyrLK
// would otherwise rebuild on every call; the match is the same bit for bit.
// An image passed again to PrepareLeft / PrepareRight is prepared into the
// buffers it holds, reused when they have the sizes needed (no allocation,
// and no page faults, from one frame to the next).
struct StereoImage {
  std::vector<cv::Mat> pyramid;
  cv::Mat equalised;  // buffer of the equalised image (options.equalize)
};

// What one StereoMatcher::Match call did with the left features it was given.
struct StereoStats {
  int matched = 0;            // right observations emitted
  int lost_flow = 0;          // LK failed or ended outside the right image
  int lost_reverse = 0;       // failed the right -> left check
  int rejected_epipolar = 0;  // off the epipolar line by > max_epipolar_px
  int rejected_depth = 0;     // triangulates behind a camera (or at infinity)
};

class StereoMatcher {
 public:
  // Left and right cameras with their extrinsics T_b_c (from sensor.yaml);
  // the relative pose T_c0_c1 = T_b_c0^-1 T_b_c1 is derived from them.
  StereoMatcher(const CameraModel& left, const CameraModel& right,
                const StereoMatcherOptions& options);

  // Matches `left_observations` (camera 0 pixels in `left`) into `right`.
  // Both images must be 8-bit grey of their camera's size and prepared alike
  // (FeatureTracker::Preprocess). Returns one camera-1 observation, with the
  // same feature_id, per accepted match (xy and velocity left zero). Throws
  // std::invalid_argument on an image of the wrong type or size.
  std::vector<FeatureObservation> Match(
      const cv::Mat& left, const cv::Mat& right,
      const std::vector<FeatureObservation>& left_observations,
      StereoStats* stats = nullptr) const;

  // The same match on images prepared beforehand (PrepareLeft,
  // PrepareRight), for a caller that prepares them on another thread or
  // while the left features are being tracked.
  std::vector<FeatureObservation> Match(
      const StereoImage& left, const StereoImage& right,
      const std::vector<FeatureObservation>& left_observations,
      StereoStats* stats = nullptr) const;
  // The same, the left -> right LK of left_observations[i] started at the
  // right pixel start[i] instead of at its left pixel (an empty `start`:
  // every one at its left pixel, as above). The checks are unchanged.
  // Throws std::invalid_argument when `start` is neither empty nor of
  // left_observations' size.
  std::vector<FeatureObservation> Match(
      const StereoImage& left, const StereoImage& right,
      const std::vector<FeatureObservation>& left_observations,
      const std::vector<cv::Point2f>& start,
      StereoStats* stats = nullptr) const;

  // `image` as Match reads it (8-bit grey of the left / right camera's size,
  // prepared as FeatureTracker::Preprocess does, else
  // std::invalid_argument). Const and independent of each other: both may
  // run on different threads at once.
  StereoImage PrepareLeft(const cv::Mat& image) const;
  StereoImage PrepareRight(const cv::Mat& image) const;
  // The same into *prepared, reusing its buffers (see StereoImage).
  void PrepareLeft(const cv::Mat& image, StereoImage* prepared) const;
  void PrepareRight(const cv::Mat& image, StereoImage* prepared) const;

  // Distance [px, right image] of the right pixel uv1 to the epipolar line
  // of the left pixel uv0; +infinity when either does not undistort.
  double EpipolarErrorPx(const Eigen::Vector2d& uv0,
                         const Eigen::Vector2d& uv1) const;

  // Depth z [m] of the point in camera 0 from the two undistorted bearings
  // (least squares on lambda0 f0 = lambda1 R f1 + t). Returns false when
  // the rays are parallel or the point is behind either camera.
  bool TriangulateDepth(const Eigen::Vector2d& xy0, const Eigen::Vector2d& xy1,
                        double* depth_c0) const;

  const Eigen::Quaterniond& q_c0_c1() const { return q_c0_c1_; }
  const Eigen::Vector3d& t_c0_c1() const { return t_c0_c1_; }

 private:
  void CheckImage(const cv::Mat& image, const CameraModel& camera,
                  const char* which) const;
  void Prepare(const cv::Mat& image, StereoImage* prepared) const;

  CameraModel left_;
  CameraModel right_;
  StereoMatcherOptions options_;
  Eigen::Quaterniond q_c0_c1_;
  Eigen::Vector3d t_c0_c1_;    // [m]
  Eigen::Matrix3d essential_;  // E = [t_c0_c1]x R_c0_c1: f0^T E f1 = 0
};

}  // namespace vio

#endif  // VIO_FRONTEND_STEREO_MATCHER_H_
