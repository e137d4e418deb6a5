#ifndef VIO_EVAL_TRACK_TRUTH_H_
#define VIO_EVAL_TRACK_TRUTH_H_

// A frontend's error in motion against exact truth, for a sequence whose
// scene is known (a rendered one: the depth of every pixel is known).
//
// Each cam0 track's first sighting is undistorted, cast as a ray from the
// camera at the frame's pose and meets the scene at X, the point the track
// is about. In every later frame the true pixel is X's projection, and
//   drift error = |tracked pixel - projection of X|        [px]
// is what the estimator sees (the track's anchor is its first sighting).
//   step error  = the same with X cast from the previous sighting
// isolates one frame-to-frame step. A cam1 sighting of feature f is
// compared with the projection into cam1 of the point cast from f's cam0
// sighting in the same frame (the stereo match error). A sighting whose
// true point is hidden from the camera (behind another surface) or out of
// its view is not an error sample: it is counted apart, as the tracker
// follows something that is no longer the point.
//
// Frames, cameras and poses: frames carry feature_id, camera and uv (as the
// frontend emits them); poses are the body's at each frame's camera stamp
// (exposure centre); T_b_c maps camera to body.

#include <Eigen/Geometry>
#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

#include "dataset/trajectory.h"
#include "eval/pixel_errors.h"
#include "geometry/camera_model.h"
#include "geometry/feature_observation.h"

namespace vio {

// The first point where the ray origin_w + t direction_w (t > 0) meets the
// scene; false when it meets none.
using RayCast = std::function<bool(const Eigen::Vector3d& origin_w,
                                   const Eigen::Vector3d& direction_w,
                                   Eigen::Vector3d* point_w)>;
// True when nothing of the scene lies between eye_w and point_w.
using VisibilityTest = std::function<bool(const Eigen::Vector3d& eye_w,
                                          const Eigen::Vector3d& point_w)>;

struct TrackLengthStats {
  size_t tracks = 0;  // distinct cam0 feature ids
  double mean = 0.0;  // cam0 frames per track
  double median = 0.0;
  double p90 = 0.0;  // nearest rank
  int max = 0;
  // Share of tracks of length 1, 2-4, 5-9, 10-19, 20-49, >= 50 frames.
  static constexpr int kBuckets = 6;
  double share[kBuckets] = {};
};

struct TrackTruthReport {
  PixelErrorStats drift;   // every later cam0 sighting vs its first
  PixelErrorStats step;    // every later cam0 sighting vs the one before
  PixelErrorStats stereo;  // cam1 sightings vs the same frame's cam0
  // Drift error by age (sightings since the first): (age, stats) for the
  // ages 1, 2, 5, 10, 20, 40 that have samples.
  std::vector<std::pair<int, PixelErrorStats>> drift_by_age;
  TrackLengthStats lengths;
  int64_t hidden = 0;               // sightings of a hidden / out-of-view point
  int64_t cast_missed = 0;          // rays that met no surface (not samples)
  int64_t frames_without_pose = 0;  // skipped frames
};

// Evaluates the tracks of `frames` (any order of observations within a
// frame, frames in stamp order). cameras[c] and T_b_c[c] belong to camera
// c; frame_poses holds a pose at each frame's stamp (a frame without one is
// skipped and counted). Throws std::invalid_argument when cameras and
// T_b_c differ in size or are empty.
TrackTruthReport EvaluateTrackTruth(const std::vector<FeatureFrame>& frames,
                                    const std::vector<CameraModel>& cameras,
                                    const std::vector<Eigen::Isometry3d>& T_b_c,
                                    const Trajectory& frame_poses,
                                    const RayCast& cast,
                                    const VisibilityTest& visible);

// Length statistics of the cam0 tracks of `frames`.
TrackLengthStats ComputeTrackLengths(const std::vector<FeatureFrame>& frames);

}  // namespace vio

#endif  // VIO_EVAL_TRACK_TRUTH_H_
