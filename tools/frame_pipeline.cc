#include "tools/frame_pipeline.h"

#include <cmath>
#include <exception>
#include <stdexcept>
#include <string>
#include <thread>

namespace vio {

void PipelineOptions::Validate() const {
  if (queue_frames < 1) {
    throw std::invalid_argument("pipeline queue_frames must be >= 1 (got " +
                                std::to_string(queue_frames) + ")");
  }
}

void RunFramePipeline(const FrameProducer& produce,
                      const FrameConsumer& consume,
                      const PipelineOptions& options) {
  options.Validate();
  if (options.sequential) {
    FeatureFrame frame;
    while (produce(&frame)) {
      consume(std::move(frame));
      frame = FeatureFrame();
    }
    return;
  }
  BoundedQueue<FeatureFrame> queue(static_cast<size_t>(options.queue_frames));
  std::exception_ptr producer_error;
  std::thread producer([&] {
    try {
      FeatureFrame frame;
      while (produce(&frame)) {
        if (!queue.Push(std::move(frame))) break;  // the consumer stopped
        frame = FeatureFrame();
      }
    } catch (...) {
      producer_error = std::current_exception();
    }
    queue.Close();
  });
  try {
    while (std::optional<FeatureFrame> frame = queue.Pop()) {
      consume(std::move(*frame));
    }
  } catch (...) {
    queue.Close();
    queue.Clear();
    producer.join();
    throw;
  }
  producer.join();
  if (producer_error) std::rethrow_exception(producer_error);
}

EstimatorOutput StreamingRunner::AddFrame(const FeatureFrame& frame) {
  const int64_t t_imu_ns =
      frame.t_ns + std::llround(estimator_->time_offset_s() * 1e9);
  ImuSample s;
  while (imu_(&s)) {
    estimator_->AddImu(s);
    if (s.t_ns >= t_imu_ns) break;
  }
  return estimator_->AddFrame(frame);
}

}  // namespace vio
