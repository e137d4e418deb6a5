#ifndef VIO_FRONTEND_DIRECT_ODOMETRY_H_
#define VIO_FRONTEND_DIRECT_ODOMETRY_H_

// Direct stereo odometry, frame to keyframe: the user's notes as a usable
// baseline beside the VIO (docs/direct.md).
//
// Per stereo pair (raw 8-bit images of the two calibrated cameras):
// 1. both images are undistorted to pinholes (frontend/pinhole_undistorter.h)
//    and turned into pyramids;
// 2. the first pair becomes the first keyframe: its semi-dense inverse depth
//    from the pair (frontend/stereo_depth.h); its left camera is the world;
// 3. every later frame is tracked against the current keyframe
//    (frontend/direct_tracker.h), both of its images when it has a right one,
//    from a constant-velocity prediction; its pose is T_w_kf delta^-1;
// 4. it becomes the new keyframe when the keyframe's points it sees drop
//    below min_overlap, or when it is farther from the keyframe than
//    max_distance_over_depth times the keyframe's median depth.
// A frame whose tracking fails (too few residuals) takes the predicted pose,
// is counted as lost and, when it has a right image, becomes a keyframe, so
// the odometry continues (with the error of that prediction).

#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <opencv2/core.hpp>

#include "frontend/direct_keyframe.h"
#include "frontend/direct_options.h"
#include "frontend/direct_tracker.h"
#include "frontend/pinhole_undistorter.h"
#include "geometry/camera_model.h"

namespace vio {

// What Process did with one stereo pair.
struct DirectFrame {
  int64_t t_ns = 0;
  Eigen::Isometry3d T_w_c = Eigen::Isometry3d::Identity();  // left camera
  bool tracked = false;    // false for the first frame and lost frames
  bool lost = false;       // tracking failed: T_w_c is the prediction
  bool keyframe = false;   // the frame became the keyframe
  TrackResult track;       // empty for the first frame
  StereoDepthStats depth;  // when depth was computed for a keyframe
};

struct DirectOdometrySummary {
  int frames = 0;
  int keyframes = 0;
  int lost = 0;            // tracking failed (see the header comment)
  int weak_keyframes = 0;  // too few depth points: the old keyframe stays
  int mono_frames = 0;     // frames given without a right image
};

class DirectOdometry {
 public:
  // The cameras' calibrations (intrinsics, distortion, T_b_c) of cam0 (left)
  // and cam1 (right). Throws std::invalid_argument when the options or the
  // calibrations do not validate.
  DirectOdometry(const CameraCalibration& left, const CameraCalibration& right,
                 const DirectOdometryOptions& options);

  // Processes the next pair, in time order. `right` may be empty (a missing
  // image): the frame is then tracked on its left image alone and cannot
  // become a keyframe. Throws std::invalid_argument for an image of the wrong
  // type or size (callers skip and count those beforehand).
  DirectFrame Process(int64_t t_ns, const cv::Mat& left, const cv::Mat& right);

  const DirectOdometrySummary& summary() const { return summary_; }
  // T_c1_c0: left-camera points into the right camera.
  const Eigen::Isometry3d& T_r_l() const { return T_r_l_; }
  const DirectKeyframe* keyframe() const { return keyframe_.get(); }

 private:
  // A keyframe from this pair, or nullptr when its depth has too few points.
  std::unique_ptr<DirectKeyframe> MakeKeyframe(int64_t t_ns,
                                               const ImagePyramid& left,
                                               const ImagePyramid& right,
                                               const Eigen::Isometry3d& T_w_c,
                                               StereoDepthStats* stats) const;

  DirectOdometryOptions options_;
  PinholeUndistorter left_undistorter_, right_undistorter_;
  Eigen::Isometry3d T_r_l_;
  DirectTracker tracker_;
  std::unique_ptr<DirectKeyframe> keyframe_;
  Eigen::Isometry3d T_w_last_ = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d velocity_ = Eigen::Isometry3d::Identity();  // last motion
  Eigen::Vector2d affine_[2];  // of the last frame, w.r.t. the keyframe
  DirectOdometrySummary summary_;
};

}  // namespace vio

#endif  // VIO_FRONTEND_DIRECT_ODOMETRY_H_
