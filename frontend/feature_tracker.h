#ifndef VIO_FRONTEND_FEATURE_TRACKER_H_
#define VIO_FRONTEND_FEATURE_TRACKER_H_

// Monocular KLT feature tracking, frame to frame, on 8-bit grey images:
//   1. pyramidal Lucas-Kanade from the previous frame
//   (cv::calcOpticalFlowPyrLK),
//   2. a forward-backward check (track back, compare with the start),
//   3. with anchor_refinement, an affine refinement of each track against its
//      first appearance (frontend/anchor_refiner.h), so that its error does
//      not add up from frame to frame nor grow as the patch deforms,
//   4. a fundamental-matrix RANSAC on undistorted points (FundamentalInliers),
//      against the previous frame and against the frame
//      fundamental_baseline_frames back,
//   5. a minimum-distance mask around surviving tracks (older tracks win), and
//      new Shi-Tomasi corners in its gaps (frontend/corner_detector.h, the
//      rule of cv::goodFeaturesToTrack) to refill the frame to max_features.
// Every track has a feature id that is unique and stays the same for as long
// as the track lives. The tracker emits pixels only (feature_id, camera, uv);
// frontend/observation_builder fills the undistorted xy and the velocity.
// It never reads files: the caller hands in images as cv::Mat.

#include <deque>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <unordered_map>
#include <vector>

#include "frontend/anchor_refiner.h"
#include "frontend/corner_detector.h"
#include "frontend/frontend_options.h"
#include "geometry/camera_model.h"
#include "geometry/feature_observation.h"

namespace vio {

// What one FeatureTracker::Track call did with the tracks it was given.
struct TrackerStats {
  int tracked = 0;    // tracks continued into this frame (after all checks)
  int lost_flow = 0;  // LK failed or ended outside the image
  int lost_forward_backward = 0;  // failed the forward-backward check
  int reanchored = 0;   // refinement against the anchor refused: renewed
  int lost_anchor = 0;  // no longer correlates with its anchor: dropped
  int rejected_fundamental = 0;  // outliers of the fundamental RANSAC
  int rejected_baseline = 0;     // outliers of the RANSAC over several frames
  int dropped_crowded = 0;       // closer than min_distance to an older track
  int created = 0;               // new Shi-Tomasi corners
};

class FeatureTracker {
 public:
  // `camera` is the calibration of the images that will come in (its size
  // and its distortion, for the fundamental check); `camera_index` is
  // written into every observation.
  FeatureTracker(const CameraModel& camera,
                 const FeatureTrackerOptions& options, int camera_index = 0);

  // Tracks the previous frame's features into `image`, removes outliers and
  // refills with new corners. Returns this frame's observations, in no
  // particular order, with feature_id, camera and uv set (xy and velocity
  // are left zero). Throws std::invalid_argument (and changes nothing) when
  // the image is empty, not 8-bit single-channel, or not of the
  // calibration's size: callers skip and count such images beforehand.
  std::vector<FeatureObservation> Track(const cv::Mat& image);

  // The image as the tracker sees it: CLAHE-equalised when enabled, else
  // `image` itself. A stereo matcher must be given the right image prepared
  // the same way.
  cv::Mat Preprocess(const cv::Mat& image) const;

  // Forgets every track (the next Track only detects); ids keep increasing.
  void Reset();

  // The last frame after Preprocess, and what the last Track did.
  const cv::Mat& image() const { return image_; }
  const TrackerStats& stats() const { return stats_; }
  const FeatureTrackerOptions& options() const { return options_; }

 private:
  // Steps 1-4 on the current tracks into `image` (its pyramid given);
  // updates points_, ids_, ages_.
  void TrackFromPrevious(const cv::Mat& image,
                         const std::vector<cv::Mat>& pyramid);
  // The RANSAC of step 4 against the frame fundamental_baseline_frames back.
  void CheckLongBaseline();
  // Step 5: thins crowded tracks and detects new corners in the gaps.
  void Refill(const cv::Mat& image);
  bool InsideBorder(const cv::Point2f& uv) const;

  CameraModel camera_;
  FeatureTrackerOptions options_;
  int camera_index_;
  cv::Ptr<cv::CLAHE> clahe_;

  cv::Mat image_;
  std::vector<cv::Mat> pyramid_;        // of image_, reused as the previous one
  std::vector<cv::Mat> spare_pyramid_;  // buffers for the next one
  std::vector<cv::Point2f> points_;     // current tracks [px]
  std::vector<int64_t> ids_;
  std::vector<int> ages_;  // frames each track has lived
  int64_t next_id_ = 0;
  AnchorRefiner anchors_;
  // The tracks' positions in the last fundamental_baseline_frames frames,
  // oldest first.
  std::deque<std::unordered_map<int64_t, cv::Point2f>> history_;
  cv::Mat image_float_;  // the current image as 32-bit float, reused
  CornerDetector detector_;
  TrackerStats stats_;
};

// The LK image pyramid of `image` for `klt` (cv::buildOpticalFlowPyramid with
// derivatives), shared by tracking and stereo matching.
std::vector<cv::Mat> BuildKltPyramid(const cv::Mat& image,
                                     const KltOptions& klt);
// The same into *pyramid, reusing its buffers when they have the sizes
// needed.
void BuildKltPyramid(const cv::Mat& image, const KltOptions& klt,
                     std::vector<cv::Mat>* pyramid);

// Lucas-Kanade from `from` into `to` (pyramids or images) for `points`,
// starting at `guess` when it is non-empty. Sets `tracked` to the result and
// `ok[i]` to whether LK converged for point i.
void TrackKlt(cv::InputArray from, cv::InputArray to, const KltOptions& klt,
              const std::vector<cv::Point2f>& points,
              const std::vector<cv::Point2f>& guess,
              std::vector<cv::Point2f>* tracked, std::vector<uchar>* ok);

// Fundamental-matrix RANSAC on the correspondences prev_uv[i] -> curr_uv[i]
// (distorted pixels of `camera`). Both sets are undistorted and rescaled to a
// virtual pinhole of focal options.virtual_focal_px centred in the image, so
// options.fundamental_threshold_px is a distance in pixels. Returns 1 for
// inliers and 0 for outliers. Points that cannot be undistorted are outliers.
// With fewer than 8 correspondences nothing can be judged and all are kept.
// Degenerate motion (pure rotation, no motion) fits a whole family of
// fundamental matrices: then only outliers that no single epipole explains
// can be found.
std::vector<uchar> FundamentalInliers(const CameraModel& camera,
                                      const std::vector<cv::Point2f>& prev_uv,
                                      const std::vector<cv::Point2f>& curr_uv,
                                      const FeatureTrackerOptions& options);

}  // namespace vio

#endif  // VIO_FRONTEND_FEATURE_TRACKER_H_
