#ifndef VIO_ESTIMATOR_SIGHTING_OUTLIERS_H_
#define VIO_ESTIMATOR_SIGHTING_OUTLIERS_H_

// Which sightings of one landmark are outliers, after an adjustment: the
// rule the running window's slide, the stereo start's outlier rounds
// (WindowProblem::Outliers) and the monocular structure from motion's rounds
// (SolveStructureFromMotion) share. Each sighting is tested on its own, so
// that one bad observation (a tracker slip, a gross outlier) costs that
// observation, not the whole landmark; a landmark with more than half of its
// tested sightings bad, or one whose error could not be evaluated, goes whole
// (its anchor, which the other sightings are measured against, is then the
// likelier culprit).

#include <vector>

namespace vio {

struct SightingVerdict {
  bool whole = false;    // remove the landmark whole
  std::vector<int> bad;  // else: the indices of the sightings to remove
};

// errors: the landmark's tested sightings' reprojection errors, in the unit of
// threshold (pixels, or whitened norms against a whitened threshold). A
// sighting is bad when its error exceeds threshold; a non-finite error makes
// the landmark go whole.
SightingVerdict ClassifySightings(const std::vector<double>& errors,
                                  double threshold);

}  // namespace vio

#endif  // VIO_ESTIMATOR_SIGHTING_OUTLIERS_H_
