#ifndef VIO_DATASET_SIM_FEATURES_H_
#define VIO_DATASET_SIM_FEATURES_H_

// The simulator's visual half (see dataset/simulator.h for the model): point
// landmarks on the faces of a room, and a per-frame imitation of a KLT
// tracker that turns them into feature observations.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <random>
#include <vector>

#include "dataset/simulator.h"
#include "geometry/camera_model.h"
#include "geometry/feature_observation.h"

namespace vio {

// `room.landmarks` points uniform over the room's floor, ceiling and four
// walls, each face's share proportional to its area.
std::vector<Eigen::Vector3d> MakeRoomLandmarks(const SimRoomOptions& room,
                                               std::mt19937* rng);

class SimFeatureTracker {
 public:
  // `landmarks_w` must outlive the tracker. `seed` drives drops, detection
  // order, pixel noise and outliers.
  SimFeatureTracker(const SimCameraOptions& options,
                    const std::vector<Eigen::Vector3d>* landmarks_w,
                    uint32_t seed);

  // The observations of the frame stamped `t_ns` (camera clock), the body
  // being at (q_w_b, p_w_b) at exposure. Appends cam0's observations, then
  // cam1's, to frame->observations and one flag each to *is_outlier.
  void Track(int64_t t_ns, const Eigen::Quaterniond& q_w_b,
             const Eigen::Vector3d& p_w_b, FeatureFrame* frame,
             std::vector<bool>* is_outlier);

  // landmark_of_feature()[id]: the landmark followed by feature `id`.
  const std::vector<int>& landmark_of_feature() const {
    return landmark_of_feature_;
  }

 private:
  struct ActiveTrack {
    int64_t feature_id;
    int landmark;
    Eigen::Vector2d uv;  // noise-free pixel in cam0 this frame
  };

  // Noise-free distorted pixel of landmark `l` in `camera`, when it is in
  // front, inside the calibrated field of view and `border_` px inside the
  // image.
  bool Visible(int camera, const Eigen::Quaterniond& q_c_w,
               const Eigen::Vector3d& p_c_w, int l, Eigen::Vector2d* uv) const;
  void DetectNew(const std::vector<std::pair<int, Eigen::Vector2d>>& visible,
                 const std::vector<bool>& taken);
  // The measured pixel: noise, or with outlier_fraction an outlier.
  Eigen::Vector2d Measure(int camera, const Eigen::Vector2d& uv, bool* outlier);

  SimCameraOptions options_;
  const std::vector<Eigen::Vector3d>* landmarks_w_;
  std::vector<CameraModel> cameras_;
  std::vector<double> max_radius_;  // of xy inside the image, per camera
  double border_;                   // [px]
  std::mt19937 rng_;
  std::vector<ActiveTrack> tracks_;
  std::vector<int> landmark_of_feature_;
};

}  // namespace vio

#endif  // VIO_DATASET_SIM_FEATURES_H_
