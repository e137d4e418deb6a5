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
// A world point (landmarks.reanchored_tracks keep_point*, Landmark::
// world_point) is recorded when it is converted (its anchor frame leaves),
// again after every step's solve while it lives (RecordWorldPoints: its
// last record is its estimate when it is marginalised, capped or released),
// and as it is at query time. A later record of a world point replaces the
// earlier ones whatever its angle: the point's estimate holds all its
// sightings, the marginalised ones through the prior. Its angle is taken
// over every sighting the point ever had (the camera centres are kept while
// it lives). A capped point's track restarts as a new landmark under the
// same feature id: the same simulated or tracked point, so it stays one
// record, the better triangulated (widest angle) of the capped point and
// the landmarks of the restarted track.
//
// A record is finished once its landmark has left the window and its track
// has ended (the newest frame does not observe it): nothing can replace it
// any more. The finished records can be taken away as the run goes
// (TakeFinished), so that a caller writing them out keeps only the window's
// in memory, however long the run. (A track that resumed after a frame
// without its feature would be a second landmark of the same id: the
// trackers never do that, an id ends with its track.)
//
// Each carries its triangulation angle: the largest angle at the point
// between the rays from the cameras that saw it in the window. Depth
// precision falls with it (about pixel noise / angle): a landmark seen over
// 0.5 deg of parallax, enough to enter the window, can be metres off, and a
// map for planning wants the ones seen over a few degrees.

#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

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

  // Records the world points of `ids` (sorted ascending) that have
  // sightings, as they are now: after every solve those not about to be
  // removed as outliers (whose solved position is suspect), and the capped
  // ones before the window forgets them.
  void RecordWorldPoints(const FeatureManager& features,
                         const CameraPoseFn& T_w_c,
                         const std::vector<int64_t>& ids);

  // Marks finished the records of landmarks that are no longer in the
  // window and not in `newest_ids` (the feature ids the newest frame
  // observed, sorted ascending).
  void Retire(const FeatureManager& features,
              const std::vector<int64_t>& newest_ids);

  // The finished records not taken yet, by feature id; they are forgotten.
  std::map<int64_t, MappedLandmark> TakeFinished();

  // The records not taken yet (finished or not) by feature id, overlaid with
  // the triangulated landmarks in the window now.
  std::map<int64_t, MappedLandmark> WithWindow(const FeatureManager& features,
                                               const CameraPoseFn& T_w_c) const;

 private:
  // One feature id's records: `live` of the landmark (or world point) the
  // id has now, `closed` the best of its earlier world points (capped or
  // released while the track went on).
  struct Record {
    MappedLandmark live;
    bool has_live = false;
    bool live_is_point = false;
    bool has_closed = false;
    MappedLandmark closed;
    // The live world point's sightings' camera centres, by (frame, camera).
    std::map<std::pair<int64_t, int>, Eigen::Vector3d> centres;
    MappedLandmark Best() const;
  };
  // Adds a record of `l` (world point or not) to `r`.
  static void Add(const Landmark& l, const CameraPoseFn& T_w_c, Record* r);

  std::map<int64_t, Record> recorded_;          // may still be replaced
  std::map<int64_t, MappedLandmark> finished_;  // final, not taken yet
};

}  // namespace vio

#endif  // VIO_ESTIMATOR_LANDMARK_MAP_H_
