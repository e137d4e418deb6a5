#ifndef VIO_ESTIMATOR_SEQUENCE_RUNNER_H_
#define VIO_ESTIMATOR_SEQUENCE_RUNNER_H_

// Feeds a whole recorded sequence (IMU stream and feature frames, both in
// stamp order) to an estimator in the order a live system would see it: before
// each frame, every IMU sample up to and including the first one at or after
// the frame's IMU time (t_cam + t_d).

#include <functional>
#include <vector>

#include "estimator/estimator.h"

namespace vio {

// Called after each frame with its index and output (for progress bars).
using FrameCallback =
    std::function<void(size_t frame_index, const EstimatorOutput& output)>;

// Runs the estimator over the sequence; returns one output per frame.
// frames must carry xy and velocity (frontend/observation_builder).
std::vector<EstimatorOutput> RunSequence(
    Estimator* estimator, const std::vector<ImuSample>& imu,
    const std::vector<FeatureFrame>& frames,
    const FrameCallback& callback = nullptr);

}  // namespace vio

#endif  // VIO_ESTIMATOR_SEQUENCE_RUNNER_H_
