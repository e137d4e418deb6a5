// The world points the marginalisation prior holds (landmarks.
// reanchored_tracks keep_point, estimator/window_problem_points.cc): a point
// whose track ends with the oldest frame leaves with that frame's
// marginalisation; one that loses its last sighting otherwise (an outlier
// removed, a non-keyframe dropped) is marginalised out of the prior here
// (estimator/point_release.h).

#include "estimator/estimator.h"
#include "estimator/point_release.h"
#include "estimator/state_prior.h"
#include "estimator/thread_cpu_time.h"

namespace vio {

void Estimator::ReleaseOrphanPoints() {
  const double cpu_start = ThreadCpuSeconds();
  const PointReleaseResult release =
      vio::ReleaseOrphanPoints(&features_, &prior_, &prior_blocks_);
  if (release.released == 0) return;
  summary_.marginalization_cpu_time_s.Add(ThreadCpuSeconds() - cpu_start);
  ++summary_.points_released;
  if (release.failed) {
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

void Estimator::DropWorldPoints() {
  std::vector<int64_t> ids;
  for (const auto& [id, l] : features_.landmarks()) {
    if (l.world_point) ids.push_back(id);
  }
  for (const int64_t id : ids) features_.Forget(id);
}

}  // namespace vio
