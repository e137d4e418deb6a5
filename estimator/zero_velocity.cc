#include "estimator/zero_velocity.h"

#include <algorithm>
#include <cmath>

namespace vio {

void ZeroVelocityDetector::AddImu(const ImuSample& sample) {
  imu_.push_back(sample);
  const int64_t window_ns = std::llround(options_.imu_window_s * 1e9);
  while (imu_.size() > 1 && sample.t_ns - imu_.front().t_ns > window_ns) {
    imu_.pop_front();
  }
}

void ZeroVelocityDetector::AddFrame(
    int64_t t_ns, const std::vector<FeatureObservation>& observations) {
  Frame f;
  f.t_ns = t_ns;
  for (const FeatureObservation& o : observations) {
    if (o.camera == 0 && o.xy.allFinite()) f.xy[o.feature_id] = o.xy;
  }
  frames_.push_back(std::move(f));
  // Keep the newest frame that is at least the span old as the reference.
  const int64_t span_ns = std::llround(options_.image_span_s * 1e9);
  while (frames_.size() > 2 && t_ns - frames_[1].t_ns >= span_ns) {
    frames_.pop_front();
  }
}

StillnessReport ZeroVelocityDetector::Check() const {
  StillnessReport r;
  const ImuStatistics s = ComputeImuStatistics(
      std::vector<ImuSample>(imu_.begin(), imu_.end()), options_.block_s);
  r.acc_block_std = s.acc_block_std.maxCoeff();
  r.gyr_block_std = s.gyr_block_std.maxCoeff();
  // One sample period of slack on the span, as the static start allows.
  r.imu_still = s.blocks >= 2 && s.duration_s >= 0.95 * options_.imu_window_s &&
                r.acc_block_std <= options_.max_acc_std &&
                r.gyr_block_std <= options_.max_gyr_std;
  if (frames_.empty()) return r;
  const Frame& newest = frames_.back();
  const Frame& reference = frames_.front();
  r.newest_has_features = !newest.xy.empty();
  const int64_t span_ns = std::llround(options_.image_span_s * 1e9);
  if (frames_.size() < 2 || newest.t_ns - reference.t_ns < span_ns) return r;
  std::vector<double> d;
  for (const auto& [id, xy] : newest.xy) {
    const auto it = reference.xy.find(id);
    if (it != reference.xy.end()) d.push_back((xy - it->second).norm());
  }
  r.common_features = static_cast<int>(d.size());
  if (r.common_features < options_.min_common_features) return r;
  std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
  r.disparity_px = focal_px_ * d[d.size() / 2];
  r.image_verdict = true;
  r.image_still = r.disparity_px <= options_.max_disparity_px;
  return r;
}

void ZeroVelocityDetector::Clear() {
  imu_.clear();
  frames_.clear();
}

}  // namespace vio
