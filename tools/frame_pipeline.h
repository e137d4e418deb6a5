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

#include <functional>
#include <utility>
#include <vector>

#include "estimator/estimator.h"
#include "geometry/feature_observation.h"
#include "tools/bounded_queue.h"

namespace vio {

struct PipelineOptions {
  bool sequential = false;  // true: produce and consume on one thread
  int queue_frames = 8;     // frames the producer may be ahead [frames], >= 1

  void Validate() const;  // throws std::invalid_argument
};

// Fills *frame with the next frame; false at the end.
using FrameProducer = std::function<bool(FeatureFrame* frame)>;
using FrameConsumer = std::function<void(FeatureFrame&& frame)>;

// Runs produce until it returns false, handing each frame to consume in
// order (see the header comment for threads and errors).
void RunFramePipeline(const FrameProducer& produce,
                      const FrameConsumer& consume,
                      const PipelineOptions& options);

// The IMU samples in stamp order, one per call: fills *sample and returns
// true, or false at the end (and on every call after it); e.g. an
// ImuCsvStream's Next (dataset/euroc_csv_stream.h), which reads them from
// the file as the replay goes.
using ImuSource = std::function<bool(ImuSample* sample)>;

// Feeds an estimator one frame at a time in RunSequence's order
// (estimator/sequence_runner.h): before each frame, every IMU sample up to
// and including the first one at or after the frame's IMU time (t_cam +
// t_d). It pulls the samples from `imu` as it needs them and holds none, so
// the IMU can be read during the run. frame_pipeline_test holds its outputs
// equal to RunSequence's.
class StreamingRunner {
 public:
  StreamingRunner(Estimator* estimator, ImuSource imu)
      : estimator_(estimator), imu_(std::move(imu)) {}

  EstimatorOutput AddFrame(const FeatureFrame& frame);

 private:
  Estimator* estimator_;
  ImuSource imu_;
};

}  // namespace vio

#endif  // VIO_TOOLS_FRAME_PIPELINE_H_
