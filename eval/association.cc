#include "eval/association.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace vio {
namespace {

void CheckNotDecreasing(const Trajectory& trajectory, const char* name) {
  for (size_t i = 1; i < trajectory.size(); ++i) {
    if (trajectory[i].t_ns < trajectory[i - 1].t_ns) {
      throw std::invalid_argument(std::string("Associate: the ") + name +
                                  " stamps decrease at index " +
                                  std::to_string(i));
    }
  }
}

// Index of the element of `stamps` (never decreasing, not empty) nearest to
// t_ns, as argmin over |stamps - t| picks it: on a tie between two stamps the
// earlier one, and of repeats of the chosen stamp the first.
size_t Nearest(const std::vector<int64_t>& stamps, int64_t t_ns) {
  const auto after = std::lower_bound(stamps.begin(), stamps.end(), t_ns);
  size_t j = 0;
  if (after == stamps.end()) {
    j = stamps.size() - 1;
  } else if (after != stamps.begin()) {
    const size_t k = static_cast<size_t>(after - stamps.begin());
    // stamps[k - 1] < t_ns <= stamps[k]; '<=' keeps the earlier one on a tie.
    j = (t_ns - stamps[k - 1] <= stamps[k] - t_ns) ? k - 1 : k;
  }
  return static_cast<size_t>(
      std::lower_bound(stamps.begin(), stamps.end(), stamps[j]) -
      stamps.begin());
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
  CheckNotDecreasing(estimate, "estimate");
  CheckNotDecreasing(ground_truth, "ground-truth");

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

NearestGroundTruth::NearestGroundTruth(const Trajectory& estimate)
    : estimate_(estimate) {
  CheckNotDecreasing(estimate, "estimate");
  nearest_.reserve(estimate.size());
}

void NearestGroundTruth::Add(const StampedState& s) {
  if (states_ > 0 && s.t_ns <= before_.t_ns) {
    throw std::invalid_argument(
        "NearestGroundTruth: the ground-truth stamps do not increase at " +
        std::to_string(s.t_ns));
  }
  // s is the first state at or after each pose's stamp t below, before_ the
  // last one before it: Nearest takes before_ when t - before_ <= s - t.
  for (; next_ < estimate_.size() && s.t_ns >= estimate_[next_].t_ns; ++next_) {
    const int64_t t = estimate_[next_].t_ns;
    nearest_.push_back(states_ > 0 && t - before_.t_ns <= s.t_ns - t ? before_
                                                                     : s);
  }
  before_ = s;
  ++states_;
}

std::vector<StampedState> NearestGroundTruth::Take() {
  // The poses after the last state take the last state.
  if (states_ > 0) {
    for (; next_ < estimate_.size(); ++next_) nearest_.push_back(before_);
  }
  return std::move(nearest_);
}

Association AssociateByIndex(const Trajectory& estimate,
                             const Trajectory& ground_truth) {
  if (estimate.size() != ground_truth.size()) {
    throw std::invalid_argument(
        "pairing by line needs as many poses in both files: the estimate has " +
        std::to_string(estimate.size()) + ", the ground truth " +
        std::to_string(ground_truth.size()));
  }
  Association out;
  out.num_estimate_in = estimate.size();
  out.num_ground_truth_in = ground_truth.size();
  out.estimate = estimate;
  out.ground_truth = ground_truth;
  return out;
}

}  // namespace vio
