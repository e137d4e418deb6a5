#ifndef VIO_EVAL_EPIPOLAR_ERROR_H_
#define VIO_EVAL_EPIPOLAR_ERROR_H_

// A frontend's tracks against known relative poses, for a recorded sequence
// with ground truth but no known scene: a track seen (cam0) in frames i and
// j = i + gap must satisfy the epipolar constraint of the ground-truth
// relative pose T_cj_ci = (T_w_b(t_j) T_b_c)^-1 T_w_b(t_i) T_b_c:
//   x_j^T E x_i = 0,   E = [t_ji]x R_ji,
// x the undistorted normalised coordinates (x, y, 1). The error of a pair
// is the distance of x_j from the line l = E x_i,
//   |x_j . l| / sqrt(l_0^2 + l_1^2)   times the camera's mean focal [px],
// i.e. in the pixels of the later image. It is blind to errors along the
// line, so it is a lower bound of the true error; it also carries the
// ground truth's own error (pose and camera-clock alignment).

#include <Eigen/Geometry>
#include <cstdint>
#include <functional>
#include <vector>

#include "eval/pixel_errors.h"
#include "geometry/camera_model.h"
#include "geometry/feature_observation.h"

namespace vio {

// The body pose at a camera stamp; false when unknown.
using PoseAt = std::function<bool(int64_t t_ns, Eigen::Isometry3d* T_w_b)>;

struct EpipolarGapStats {
  int gap = 0;            // frames between the two sightings
  PixelErrorStats error;  // [px]
};

struct EpipolarReport {
  std::vector<EpipolarGapStats> gaps;  // gap = 1 .. max_gap
  int64_t frames_without_pose = 0;     // their sightings are not used
  // Pairs whose baseline is below 1 mm: the line is undefined, skipped.
  int64_t pairs_without_baseline = 0;
};

// Epipolar errors of the cam0 tracks of `frames` (in stamp order) for gaps
// of 1 to max_gap frames. Throws std::invalid_argument when max_gap < 1.
EpipolarReport EvaluateEpipolarError(const std::vector<FeatureFrame>& frames,
                                     const CameraModel& camera,
                                     const Eigen::Isometry3d& T_b_c,
                                     const PoseAt& pose_at, int max_gap = 6);

}  // namespace vio

#endif  // VIO_EVAL_EPIPOLAR_ERROR_H_
