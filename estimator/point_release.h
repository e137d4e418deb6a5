#ifndef VIO_ESTIMATOR_POINT_RELEASE_H_
#define VIO_ESTIMATOR_POINT_RELEASE_H_

// The release of world points (landmarks.reanchored_tracks keep_point) that
// lost their last sighting apart from a frame's marginalisation: an outlier
// removed, a non-keyframe dropped (estimator/feature_manager.h, OrphanPoints).
// The prior is their only factor, so each such point is marginalised out of
// the prior alone:
//   prior r = r0 + J dx over [kept k | points m], H = J^T J, g = J^T r0 at
//   the current values;  H* = H_kk - H_km H_mm^+ H_mk,
//   g* = g_k - H_km H_mm^+ g_m   (estimator/marginalization.h)
// which leaves the kept blocks' values as they are (the minimiser of the
// prior over the kept blocks is the same with or without the points) and
// the prior 3 tangent dimensions smaller per point.

#include <memory>
#include <vector>

#include "estimator/feature_manager.h"
#include "estimator/marginalization.h"
#include "factors/marginalization_prior.h"

namespace vio {

struct PointReleaseResult {
  // Orphan points whose block the prior held: marginalised out of it.
  int released = 0;
  // Orphans deleted from the feature manager (the released ones among them).
  int forgotten = 0;
  // The marginalisation of the released points failed: *prior and
  // *prior_blocks are as they were and still refer to the forgotten points'
  // (deleted) blocks, so the caller must replace the prior at once.
  bool failed = false;
  MarginalizationResult marginalization;  // when released > 0
};

// Marginalises the orphan world points of `features` out of *prior (blocks
// *prior_blocks, in its parameter order; prior may be null, prior_blocks
// then empty), replaces *prior and *prior_blocks by the result (the other
// blocks in the same order) and deletes every orphan from `features`.
// An orphan the prior does not hold is only deleted.
PointReleaseResult ReleaseOrphanPoints(
    FeatureManager* features, std::unique_ptr<MarginalizationPrior>* prior,
    std::vector<double*>* prior_blocks);

}  // namespace vio

#endif  // VIO_ESTIMATOR_POINT_RELEASE_H_
