#ifndef VIO_FRONTEND_IMAGE_FRONTEND_H_
#define VIO_FRONTEND_IMAGE_FRONTEND_H_

// The frontend as a whole: KLT tracking on cam0 and, in stereo, matching of
// every cam0 feature into cam1. Turns one (left, right) image pair into one
// FeatureFrame of pixel observations; the undistorted xy and the velocity
// are filled afterwards by frontend/observation_builder, exactly as for the
// observations of a simulated features.csv.

#include <cstdint>
#include <memory>
#include <opencv2/core.hpp>
#include <unordered_map>

#include "frontend/feature_tracker.h"
#include "frontend/frontend_options.h"
#include "frontend/stereo_matcher.h"
#include "geometry/camera_model.h"
#include "geometry/feature_observation.h"

namespace vio {

// What the last ImageFrontend::Process call did.
struct FrontendStats {
  TrackerStats tracker;
  StereoStats stereo;
  bool stereo_matched = false;  // false in mono, or when the right was empty
};

// A frame between ImageFrontend's steps (TrackLeft, then MatchRight).
struct TrackedFrame {
  FeatureFrame frame;  // cam0 observations, then the cam1 matches
  cv::Mat left;        // the left image as the tracker saw it (Preprocess)
  FrontendStats stats;
};

class ImageFrontend {
 public:
  // `cam1` is required when options.stereo and ignored otherwise. Throws
  // std::invalid_argument on invalid options or a missing cam1.
  ImageFrontend(const CameraModel& cam0, const CameraModel* cam1,
                const FrontendOptions& options);

  // Tracks `left` (cam0) and, in stereo with a non-empty `right`, matches
  // into it; an empty `right` (a missing cam1 image) gives a cam0-only
  // frame. Images must be 8-bit grey of their camera's size, else
  // std::invalid_argument (callers skip and count such images first).
  FeatureFrame Process(int64_t t_ns, const cv::Mat& left,
                       const cv::Mat& right = cv::Mat());

  // Process in steps, for a caller that runs them on different threads
  // (tools/image_tracks.h): TrackLeft carries the tracker's state from frame
  // to frame and must see the frames in order; PrepareRight is const and
  // MatchRight touches only its own buffers, so both may run on other
  // threads meanwhile (MatchRight of frame k while TrackLeft takes frame
  // k + 1; MatchRight on one thread at a time). Process(t, left, right) is
  // TrackLeft, PrepareRight, MatchRight, bit for bit.
  TrackedFrame TrackLeft(int64_t t_ns, const cv::Mat& left);
  // The right image prepared for matching into *prepared, reusing its
  // buffers (StereoImage); left empty for an empty `right` or in mono.
  void PrepareRight(const cv::Mat& right, StereoImage* prepared) const;
  // Adds the matches of `tracked`'s cam0 features into the prepared right
  // image (nothing when `right` is empty) and sets tracked->stats. The left
  // image is prepared into buffers kept from call to call. With
  // stereo_matcher.start_from_previous the match starts from the offsets of
  // the last MatchRight's matches, so MatchRight, like TrackLeft, must see
  // the frames in order.
  void MatchRight(const StereoImage& right, TrackedFrame* tracked);

  bool stereo() const { return matcher_ != nullptr; }
  const FrontendStats& stats() const { return stats_; }

 private:
  FeatureTracker tracker_;
  std::unique_ptr<StereoMatcher> matcher_;
  // CLAHE for the right images (when tracker.clahe): cv::CLAHE keeps
  // buffers, so the right image, prepared on its own thread, has its own.
  cv::Ptr<cv::CLAHE> right_clahe_;
  StereoImage left_;   // MatchRight's buffers for the prepared left image
  StereoImage right_;  // Process's buffers for the prepared right image
  bool start_from_previous_ = false;
  // The last matched frame's right minus left pixel per feature id [px].
  std::unordered_map<int64_t, cv::Point2f> previous_offset_;
  FrontendStats stats_;
};

}  // namespace vio

#endif  // VIO_FRONTEND_IMAGE_FRONTEND_H_
