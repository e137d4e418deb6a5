#ifndef VIO_GEOMETRY_FEATURE_OBSERVATION_H_
#define VIO_GEOMETRY_FEATURE_OBSERVATION_H_

// The plain per-frame feature data that reaches the estimator. It lives in
// geometry because its producers (frontend/ from images, dataset/ from a
// features.csv) and its consumer (estimator/) all sit above geometry in the
// dependency table and must not depend on each other.

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace vio {

// One feature seen by one camera in one frame.
struct FeatureObservation {
  int64_t feature_id = -1;  // the same id in every camera and frame
  int camera = 0;           // 0: cam0 (left), 1: cam1 (right)
  // Measured pixel, distorted, as the camera sees it [px].
  Eigen::Vector2d uv = Eigen::Vector2d::Zero();
  // Undistorted normalised image coordinates (x / z, y / z) [-].
  Eigen::Vector2d xy = Eigen::Vector2d::Zero();
  // d xy / dt, from the previous frame's observation of the same feature in
  // the same camera [1/s]; zero when the feature is new.
  Eigen::Vector2d velocity = Eigen::Vector2d::Zero();
};

// All observations of one camera frame (both cameras of a stereo pair share
// the stamp).
struct FeatureFrame {
  int64_t t_ns = 0;  // camera stamp [ns]
  std::vector<FeatureObservation> observations;
};

}  // namespace vio

#endif  // VIO_GEOMETRY_FEATURE_OBSERVATION_H_
