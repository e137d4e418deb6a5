#include "estimator/sequence_runner.h"

#include <cmath>

namespace vio {

std::vector<EstimatorOutput> RunSequence(
    Estimator* estimator, const std::vector<ImuSample>& imu,
    const std::vector<FeatureFrame>& frames, const FrameCallback& callback) {
  std::vector<EstimatorOutput> outputs;
  outputs.reserve(frames.size());
  size_t next_imu = 0;
  for (size_t i = 0; i < frames.size(); ++i) {
    const int64_t t_imu_ns =
        frames[i].t_ns + std::llround(estimator->time_offset_s() * 1e9);
    while (next_imu < imu.size()) {
      const ImuSample& s = imu[next_imu++];
      estimator->AddImu(s);
      if (s.t_ns >= t_imu_ns) break;
    }
    outputs.push_back(estimator->AddFrame(frames[i]));
    if (callback) callback(i, outputs.back());
  }
  return outputs;
}

}  // namespace vio
