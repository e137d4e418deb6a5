#include "eval/association.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace vio {
namespace {

void CheckIncreasing(const Trajectory& trajectory, const char* name) {
  for (size_t i = 1; i < trajectory.size(); ++i) {
    if (trajectory[i].t_ns <= trajectory[i - 1].t_ns) {
      throw std::invalid_argument(std::string("Associate: the ") + name +
                                  " stamps are not strictly increasing at "
                                  "index " +
                                  std::to_string(i));
    }
  }
}

// Index of the element of `stamps` (strictly increasing, not empty) nearest
// to t_ns; on an exact tie the earlier one, as argmin over |stamps - t| does.
size_t Nearest(const std::vector<int64_t>& stamps, int64_t t_ns) {
  const auto after = std::lower_bound(stamps.begin(), stamps.end(), t_ns);
  if (after == stamps.begin()) return 0;
  if (after == stamps.end()) return stamps.size() - 1;
  const size_t j = static_cast<size_t>(after - stamps.begin());
  // stamps[j - 1] < t_ns <= stamps[j]; '<=' keeps the earlier one on a tie.
  return (t_ns - stamps[j - 1] <= stamps[j] - t_ns) ? j - 1 : j;
}

}  // namespace

void AssociationOptions::Validate() const {
  if (!std::isfinite(max_diff) || max_diff < 0.0) {
    throw std::invalid_argument(
        "max_diff must be a finite number >= 0 s (got " +
        std::to_string(max_diff) + ")");
  }
}

Association Associate(const Trajectory& estimate,
                      const Trajectory& ground_truth,
                      const AssociationOptions& options) {
  options.Validate();
  CheckIncreasing(estimate, "estimate");
  CheckIncreasing(ground_truth, "ground-truth");

  Association out;
  out.num_estimate_in = estimate.size();
  out.num_ground_truth_in = ground_truth.size();
  // evo: the second trajectory (the estimate) is "long" only when it has
  // strictly more poses; otherwise it is the one walked.
  out.walked_estimate = estimate.size() <= ground_truth.size();
  if (estimate.empty() || ground_truth.empty()) return out;

  const Trajectory& walked = out.walked_estimate ? estimate : ground_truth;
  const Trajectory& searched = out.walked_estimate ? ground_truth : estimate;
  std::vector<int64_t> stamps;
  stamps.reserve(searched.size());
  for (const StampedPose& p : searched) stamps.push_back(p.t_ns);

  const int64_t max_diff_ns = std::llround(options.max_diff * 1e9);
  Trajectory& walked_out =
      out.walked_estimate ? out.estimate : out.ground_truth;
  Trajectory& searched_out =
      out.walked_estimate ? out.ground_truth : out.estimate;
  for (const StampedPose& p : walked) {
    const size_t j = Nearest(stamps, p.t_ns);
    if (std::llabs(stamps[j] - p.t_ns) > max_diff_ns) continue;
    walked_out.push_back(p);
    searched_out.push_back(searched[j]);
  }
  return out;
}

}  // namespace vio
