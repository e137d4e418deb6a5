#ifndef VIO_ESTIMATOR_VISUAL_TRACKER_H_
#define VIO_ESTIMATOR_VISUAL_TRACKER_H_

// The pose of a new frame from vision alone, for when the IMU cannot say how
// the body moved (a gap in the IMU stream): a motion-only bundle adjustment
// (the PnP problem solved iteratively) of the frame's body pose against the
// window's triangulated landmarks, with the window's poses, the landmarks'
// inverse depths and the extrinsics held fixed.
//
// Each observation of a triangulated landmark (anchor a: camera 0 of window
// frame i) by camera c of the new frame j gives the window's own visual
// factor with every block but pose_j constant:
//   c = 0: ReprojectionFactor               (pose_i, pose_j, T_b_c0, rho)
//   c = 1: StereoTwoFrameReprojectionFactor (pose_i, pose_j, T_b_c0, T_b_c1,
//                                            rho)
// under the visual options' robust kernel, started from a guess (the
// estimator extrapolates the newest frame's velocity and angular rate).

#include <Eigen/Geometry>
#include <array>
#include <vector>

#include "estimator/feature_manager.h"
#include "estimator/window.h"
#include "factors/visual_factor_options.h"
#include "geometry/feature_observation.h"

namespace vio {

struct VisualTrackerSettings {
  std::array<double, kMaxCameras> focal_px{460.0, 460.0};  // [px]
  VisualFactorOptions visual;
  // Matched landmarks needed, and inliers after the solve [-].
  int min_landmarks = 8;
  // An inlier reprojects within this after the solve [px].
  double inlier_threshold_px = 5.0;
  int max_iterations = 10;  // Levenberg-Marquardt iterations [-]
};

struct VisualPose {
  bool ok = false;  // enough inliers and a finite, converged pose
  Eigen::Isometry3d T_w_b = Eigen::Isometry3d::Identity();
  int landmarks = 0;  // observations of triangulated window landmarks
  int inliers = 0;    // of those, within inlier_threshold_px after the solve
};

// Tracks the frame seen in `observations` (normalised xy set; cameras beyond
// the window's are ignored) from guess_T_w_b. Reads the window and the
// landmarks, never changes them. A non-finite guess gives ok = false.
VisualPose TrackPoseOnLandmarks(
    const Window& window, const FeatureManager& features,
    const std::vector<FeatureObservation>& observations,
    const Eigen::Isometry3d& guess_T_w_b,
    const VisualTrackerSettings& settings);

}  // namespace vio

#endif  // VIO_ESTIMATOR_VISUAL_TRACKER_H_
