#ifndef VIO_ESTIMATOR_FEATURE_MANAGER_H_
#define VIO_ESTIMATOR_FEATURE_MANAGER_H_

// Landmark bookkeeping of the window: which frame and camera saw which
// feature, where, and each landmark's inverse depth in its anchor camera.
//
// A landmark's anchor is always its first camera-0 sighting (the oldest window
// frame whose camera 0 saw it; the visual factors anchor in camera 0). Its
// position in the anchor camera is
//   p_c = (x, y, 1) / rho,      rho: inverse depth [1/m], (x, y) the anchor's
// normalised coordinate (DESIGN.md, landmark block). When the anchor frame
// leaves the window the landmark is re-anchored on its next sighting, keeping
// its world position.
//
// With landmarks.reanchored_tracks keep_point a landmark whose anchor leaves
// while its track goes on becomes a world point instead (Landmark::
// world_point, converted by WindowProblem::OldestFrameMarginalization): no
// anchor, every sighting a residual, its coordinates a block the
// marginalisation prior holds. Such a landmark is never deleted here: when
// its last sighting goes (or it is removed) it stays as an orphan with no
// sightings until the estimator has marginalised its point out of the prior
// (OrphanPoints, Forget).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <vector>

#include "estimator/estimator_options.h"
#include "estimator/triangulation.h"
#include "geometry/feature_observation.h"

namespace vio {

// One observation of a landmark in a window frame.
struct Sighting {
  int64_t frame_id = 0;
  int camera = 0;
  Eigen::Vector2d xy = Eigen::Vector2d::Zero();        // normalised [-]
  Eigen::Vector2d velocity = Eigen::Vector2d::Zero();  // d xy / dt [1/s]
};

struct Landmark {
  int64_t feature_id = -1;
  std::vector<Sighting> sightings;  // ordered by (frame_id, camera)
  bool triangulated = false;        // inverse_depth holds an estimate
  double inverse_depth = 0.0;       // in the anchor camera [1/m]
  // A point in the world (keep_point, see the header comment): then
  // triangulated is false and inverse_depth unused; p_w is the parameter
  // block the prior refers to by address.
  bool world_point = false;
  std::array<double, 3> p_w{};  // [m]
  // p_w when it became a world point: where its factors' Jacobians are
  // taken with first estimates (WindowProblemSettings) [m].
  std::array<double, 3> p_w_first{};

  // Index of the first camera-0 sighting, -1 when camera 0 never saw it.
  int AnchorIndex() const {
    for (size_t i = 0; i < sightings.size(); ++i) {
      if (sightings[i].camera == 0) return static_cast<int>(i);
    }
    return -1;
  }
  bool HasAnchor() const { return AnchorIndex() >= 0; }
  // Requires HasAnchor().
  const Sighting& anchor() const { return sightings[AnchorIndex()]; }
};

// What AddFrame did with a frame's observations.
struct FrameAddStats {
  int added = 0;    // observations stored
  int tracked = 0;  // camera-0 features seen before in the window
  int skipped = 0;  // rejected: non-finite, unknown camera, duplicate
};

// The pose of camera `camera` of window frame `frame_id` in the world.
using CameraPoseFn =
    std::function<Eigen::Isometry3d(int64_t frame_id, int camera)>;

class FeatureManager {
 public:
  // num_cameras: 1 (mono) or 2 (stereo); other cameras' observations are
  // skipped.
  explicit FeatureManager(int num_cameras) : num_cameras_(num_cameras) {}

  // Stores the observations of a new frame. Frame ids must increase from call
  // to call (std::invalid_argument otherwise). An observation with a
  // non-finite coordinate or velocity, an unknown camera or a feature id
  // repeated within one camera is skipped and counted.
  FrameAddStats AddFrame(int64_t frame_id,
                         const std::vector<FeatureObservation>& observations);

  // Median distance [-] on the normalised plane between the camera-0
  // observations of frames a and b of the features both saw, and their count.
  // (Times the focal length it is the parallax in pixels.) The median, not
  // VINS-Mono's mean: one tracker slip of 300 px moves a 150-feature mean by
  // 2 px, and 10 % of them would make every frame a keyframe.
  double MedianParallax(int64_t frame_a, int64_t frame_b, int* common) const;

  // Removes every sighting in the frame. A triangulated landmark anchored
  // there is re-anchored on its next camera-0 sighting through the camera
  // poses (which must still hold the leaving frame); one without such a
  // sighting, or whose new depth is not positive, falls back to
  // untriangulated. A landmark with no sightings left is deleted.
  void RemoveFrame(int64_t frame_id, const CameraPoseFn& T_w_c);

  // Triangulates every untriangulated landmark that has an anchor from all
  // its sightings (the anchor as the reference view). Returns how many
  // succeeded.
  int TriangulateNew(const CameraPoseFn& T_w_c,
                     const TriangulationOptions& options);

  // The landmark's position in the world from its inverse depth (a world
  // point: p_w) [m].
  // Requires landmark.HasAnchor().
  static Eigen::Vector3d WorldPoint(const Landmark& landmark,
                                    const CameraPoseFn& T_w_c);

  // Deletes the landmark; a world point loses its sightings instead (an
  // orphan, see the header comment).
  void RemoveLandmark(int64_t feature_id);
  // Removes one sighting (nothing when absent). When it was the anchor the
  // landmark is re-anchored untriangulated (its depth belonged to the
  // removed bearing); a landmark left without sightings is deleted (a world
  // point becomes an orphan).
  void RemoveSighting(int64_t feature_id, int64_t frame_id, int camera);
  // The world points without sightings, by feature id.
  std::vector<int64_t> OrphanPoints() const;
  // Deletes the landmark whatever it is (a world point once its block has
  // left the prior).
  void Forget(int64_t feature_id) { landmarks_.erase(feature_id); }
  void Clear() { landmarks_.clear(); }

  // By feature id, so iteration is deterministic.
  std::map<int64_t, Landmark>& landmarks() { return landmarks_; }
  const std::map<int64_t, Landmark>& landmarks() const { return landmarks_; }
  int num_cameras() const { return num_cameras_; }

 private:
  int num_cameras_;
  int64_t last_frame_id_ = std::numeric_limits<int64_t>::min();
  std::map<int64_t, Landmark> landmarks_;
};

// The keyframe decision for a new frame against the last keyframe.
struct KeyframeDecision {
  bool is_keyframe = false;
  double parallax_px = 0.0;  // median over the common features [px]
  int common_features = 0;   // seen by both frames, camera 0 [-]
};

// A keyframe when fewer than options.min_tracked_features camera-0 features
// of the new frame are also in the last keyframe, or when their median parallax
// times focal_px reaches options.min_parallax_px.
KeyframeDecision DecideKeyframe(const FeatureManager& features,
                                int64_t last_keyframe_id, int64_t new_frame_id,
                                double focal_px,
                                const KeyframeOptions& options);

}  // namespace vio

#endif  // VIO_ESTIMATOR_FEATURE_MANAGER_H_
