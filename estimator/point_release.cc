#include "estimator/point_release.h"

#include <algorithm>

#include "factors/pose_manifold.h"

namespace vio {

PointReleaseResult ReleaseOrphanPoints(
    FeatureManager* features, std::unique_ptr<MarginalizationPrior>* prior,
    std::vector<double*>* prior_blocks) {
  PointReleaseResult out;
  const std::vector<int64_t> orphans = features->OrphanPoints();
  if (orphans.empty()) return out;
  std::vector<const double*> leaving;
  for (const int64_t id : orphans) {
    const double* p_w = features->landmarks().at(id).p_w.data();
    if (std::count(prior_blocks->begin(), prior_blocks->end(), p_w) != 0) {
      leaving.push_back(p_w);
    }
  }
  if (!leaving.empty() && *prior) {
    // The prior alone: the orphans have no other factor.
    const PoseManifold pose_manifold;
    MarginalizationProblem m;
    for (size_t b = 0; b < prior_blocks->size(); ++b) {
      const PriorBlock& block = (*prior)->blocks()[b];
      m.parameter_blocks.push_back(
          {(*prior_blocks)[b], block.AmbientSize(),
           block.kind == PriorBlockKind::kPose ? &pose_manifold : nullptr,
           false});
    }
    m.residual_blocks.push_back({prior->get(), nullptr, *prior_blocks});
    m.marginalized = leaving;
    out.released = static_cast<int>(leaving.size());
    out.marginalization = Marginalize(m);
    if (out.marginalization.ok()) {
      *prior = out.marginalization.MakePrior();
      *prior_blocks = out.marginalization.kept_parameter_blocks;
    } else {
      out.failed = true;
    }
  }
  // After the marginalisation: it reads the points' values.
  for (const int64_t id : orphans) features->Forget(id);
  out.forgotten = static_cast<int>(orphans.size());
  return out;
}

}  // namespace vio
