#ifndef VIO_TOOLS_FRAME_PIPELINE_H_
#define VIO_TOOLS_FRAME_PIPELINE_H_

// A two-stage pipeline for replaying images: a producer (reading and
// tracking images into feature frames) on its own thread, a consumer (the
// estimator) on the caller's, joined by a bounded queue so the producer is
// never more than `queue_frames` frames ahead. The consumer sees the same
// frames in the same order as when the two run one after the other on one
// thread (`sequential`), so the output is bit-for-bit the same.
//
// Errors: an exception thrown by the producer stops it and is rethrown on
// the caller's thread (same type, same message) once the consumer has taken
// every frame produced before it; one thrown by the consumer stops the
// producer (the queue is closed, unblocking it) and is rethrown after the
// producer's thread has joined. Neither can hang or terminate the process.

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <mutex>
#include <optional>
#include <vector>

#include "estimator/estimator.h"
#include "geometry/feature_observation.h"

namespace vio {

struct PipelineOptions {
  bool sequential = false;  // true: produce and consume on one thread
  int queue_frames = 8;     // frames the producer may be ahead [frames], >= 1

  void Validate() const;  // throws std::invalid_argument
};

// A bounded first-in first-out queue for two threads.
template <typename T>
class BoundedQueue {
 public:
  explicit BoundedQueue(size_t capacity) : capacity_(capacity) {}

  // Blocks while full; false (and `item` dropped) once the queue is closed.
  bool Push(T item) {
    std::unique_lock<std::mutex> lock(mutex_);
    not_full_.wait(lock, [&] { return closed_ || items_.size() < capacity_; });
    if (closed_) return false;
    items_.push_back(std::move(item));
    not_empty_.notify_one();
    return true;
  }

  // Blocks while empty and open; std::nullopt once closed and drained.
  std::optional<T> Pop() {
    std::unique_lock<std::mutex> lock(mutex_);
    not_empty_.wait(lock, [&] { return closed_ || !items_.empty(); });
    if (items_.empty()) return std::nullopt;
    T item = std::move(items_.front());
    items_.pop_front();
    not_full_.notify_one();
    return item;
  }

  // No more pushes; wakes both sides. Items already queued can still be
  // popped.
  void Close() {
    std::lock_guard<std::mutex> lock(mutex_);
    closed_ = true;
    not_full_.notify_all();
    not_empty_.notify_all();
  }

  // Drops the queued items (the consumer gave up).
  void Clear() {
    std::lock_guard<std::mutex> lock(mutex_);
    items_.clear();
    not_full_.notify_all();
  }

 private:
  const size_t capacity_;
  std::mutex mutex_;
  std::condition_variable not_full_;
  std::condition_variable not_empty_;
  std::deque<T> items_;
  bool closed_ = false;
};

// Fills *frame with the next frame; false at the end.
using FrameProducer = std::function<bool(FeatureFrame* frame)>;
using FrameConsumer = std::function<void(FeatureFrame&& frame)>;

// Runs produce until it returns false, handing each frame to consume in
// order (see the header comment for threads and errors).
void RunFramePipeline(const FrameProducer& produce,
                      const FrameConsumer& consume,
                      const PipelineOptions& options);

// Feeds an estimator one frame at a time in RunSequence's order
// (estimator/sequence_runner.h): before each frame, every IMU sample up to
// and including the first one at or after the frame's IMU time (t_cam +
// t_d). frame_pipeline_test holds its outputs equal to RunSequence's.
class StreamingRunner {
 public:
  StreamingRunner(Estimator* estimator, const std::vector<ImuSample>* imu)
      : estimator_(estimator), imu_(imu) {}

  EstimatorOutput AddFrame(const FeatureFrame& frame);

 private:
  Estimator* estimator_;
  const std::vector<ImuSample>* imu_;
  size_t next_imu_ = 0;
};

}  // namespace vio

#endif  // VIO_TOOLS_FRAME_PIPELINE_H_
