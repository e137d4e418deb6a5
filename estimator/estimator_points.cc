// The world points the marginalisation prior holds (landmarks.
// reanchored_tracks keep_point, estimator/window_problem_points.cc): a point
// whose track ends with the oldest frame leaves with that frame's
// marginalisation; one that loses its last sighting otherwise (an outlier
// removed, a non-keyframe dropped) is marginalised out of the prior here.

#include <time.h>

#include <algorithm>

#include "estimator/estimator.h"
#include "estimator/marginalization.h"
#include "estimator/state_prior.h"
#include "factors/pose_manifold.h"

namespace vio {
namespace {

// CPU time of the calling thread [s] (as estimator_window.cc's).
double ThreadCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

}  // namespace

void Estimator::ReleaseOrphanPoints() {
  const std::vector<int64_t> orphans = features_.OrphanPoints();
  if (orphans.empty()) return;
  std::vector<const double*> leaving;
  for (const int64_t id : orphans) {
    const double* p_w = features_.landmarks().at(id).p_w.data();
    if (std::count(prior_blocks_.begin(), prior_blocks_.end(), p_w) != 0) {
      leaving.push_back(p_w);
    }
  }
  if (!leaving.empty() && prior_) {
    // The prior alone: the orphans have no other factor.
    const PoseManifold pose_manifold;
    MarginalizationProblem m;
    for (size_t b = 0; b < prior_blocks_.size(); ++b) {
      const PriorBlock& block = prior_->blocks()[b];
      m.parameter_blocks.push_back(
          {prior_blocks_[b], block.AmbientSize(),
           block.kind == PriorBlockKind::kPose ? &pose_manifold : nullptr,
           false});
    }
    m.residual_blocks.push_back({prior_.get(), nullptr, prior_blocks_});
    m.marginalized = leaving;
    const double cpu_start = ThreadCpuSeconds();
    const MarginalizationResult result = Marginalize(m);
    summary_.marginalization_cpu_time_s.Add(ThreadCpuSeconds() - cpu_start);
    ++summary_.points_released;
    if (result.ok()) {
      prior_ = result.MakePrior();
      prior_blocks_ = result.kept_parameter_blocks;
    } else {
      ++summary_.marginalization_failures;
      WindowFrame& oldest = *window_.frames.front();
      prior_ = MakeStatePrior(oldest.pose.data(), oldest.speed_bias.data(),
                              options_.state_prior,
                              options_.state_prior.velocity_moving);
      prior_blocks_ = {oldest.pose.data(), oldest.speed_bias.data()};
      SetExtrinsicPrior();
      DropWorldPoints();
    }
  }
  for (const int64_t id : orphans) features_.Forget(id);
}

void Estimator::DropWorldPoints() {
  std::vector<int64_t> ids;
  for (const auto& [id, l] : features_.landmarks()) {
    if (l.world_point) ids.push_back(id);
  }
  for (const int64_t id : ids) features_.Forget(id);
}

}  // namespace vio
