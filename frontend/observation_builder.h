#ifndef VIO_FRONTEND_OBSERVATION_BUILDER_H_
#define VIO_FRONTEND_OBSERVATION_BUILDER_H_

// The step every feature observation takes before the estimator sees it,
// whether it came from the image tracker or from a features.csv: the measured
// (distorted) pixel uv becomes undistorted normalised coordinates xy through
// the camera model, and the image velocity d xy / dt is taken from the same
// feature's observation in the same camera's previous frame:
//
//   velocity = (xy_k - xy_{k-1}) / (t_k - t_{k-1})   [1/s]
//
// and zero when the feature was not seen in that camera's previous frame (a
// new track, or one that skipped a frame). VINS-Mono uses the same velocity to
// compensate the camera-IMU time offset.

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "geometry/camera_model.h"
#include "geometry/feature_observation.h"

namespace vio {

// What Process() removed, cumulative over all frames.
struct ObservationBuilderSummary {
  int64_t frames = 0;               // frames processed
  int64_t observations = 0;         // observations kept
  int64_t unknown_camera = 0;       // camera index without a model: removed
  int64_t outside_image = 0;        // pixel outside the image: removed
  int64_t failed_undistortion = 0;  // Undistort did not converge: removed
};

// Stateful over a sequence: it remembers each camera's previous frame.
class ObservationBuilder {
 public:
  // cameras[i] is the model of camera index i.
  explicit ObservationBuilder(std::vector<CameraModel> cameras);

  // Fills xy and velocity of every observation of `frame` (uv and camera
  // must be set), removing, and counting, those of an unknown camera, whose
  // pixel lies outside the image (CameraModel::InImage; a non-finite pixel
  // included) or whose pixel cannot be undistorted. Frames must come in
  // strictly increasing stamp order; throws std::invalid_argument otherwise.
  void Process(FeatureFrame* frame);

  const ObservationBuilderSummary& summary() const { return summary_; }

 private:
  // One camera's previous frame: its stamp and each feature's xy.
  struct PreviousFrame {
    bool valid = false;
    int64_t t_ns = 0;
    std::unordered_map<int64_t, Eigen::Vector2d> xy_by_id;
  };

  std::vector<CameraModel> cameras_;
  std::vector<PreviousFrame> previous_;  // per camera
  bool started_ = false;
  int64_t last_t_ns_ = 0;
  ObservationBuilderSummary summary_;
};

}  // namespace vio

#endif  // VIO_FRONTEND_OBSERVATION_BUILDER_H_
