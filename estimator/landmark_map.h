#ifndef VIO_ESTIMATOR_LANDMARK_MAP_H_
#define VIO_ESTIMATOR_LANDMARK_MAP_H_

// The landmarks a run has mapped, in the world frame, for users downstream of
// the estimator (vio_replay's landmarks.csv, the planner's occupancy grid).
// The window forgets a landmark once its last sighting leaves; this keeps
// its position. A landmark is recorded when its anchor frame is marginalised
// (its depth then carries every sighting of the full window) and again each
// time a later anchor leaves, and the landmarks still in the window are
// added at query time as they are then; of these records the one with the
// widest triangulation angle is kept (the later ones rest on fewer
// sightings, their first ones having left the window). Read-only for the
// estimation: nothing here feeds back into the window.
//
// Each carries its triangulation angle: the largest angle at the point
// between the rays from the cameras that saw it in the window. Depth
// precision falls with it (about pixel noise / angle): a landmark seen over
// 0.5 deg of parallax, enough to enter the window, can be metres off, and a
// map for planning wants the ones seen over a few degrees.

#include <Eigen/Core>
#include <cstdint>
#include <map>

#include "estimator/feature_manager.h"

namespace vio {

struct MappedLandmark {
  Eigen::Vector3d p_w = Eigen::Vector3d::Zero();  // [m]
  double parallax_deg = 0.0;  // triangulation angle when recorded [deg]
  int sightings = 0;          // in the window when recorded [-]
};

class LandmarkMap {
 public:
  // Records every triangulated landmark (finite, positive inverse depth)
  // anchored in frame_id, which must still be in the window (T_w_c must
  // know it and every frame that saw the landmark).
  void RecordAnchoredIn(const FeatureManager& features, int64_t frame_id,
                        const CameraPoseFn& T_w_c);

  // The recorded landmarks by feature id, overlaid with the triangulated
  // landmarks in the window now.
  std::map<int64_t, MappedLandmark> WithWindow(const FeatureManager& features,
                                               const CameraPoseFn& T_w_c) const;

 private:
  std::map<int64_t, MappedLandmark> landmarks_;
};

}  // namespace vio

#endif  // VIO_ESTIMATOR_LANDMARK_MAP_H_
