#ifndef VIO_DATASET_FRAME_FAULTS_H_
#define VIO_DATASET_FRAME_FAULTS_H_

// Faults of the camera stream, applied on purpose to a sequence's frames
// (every camera's observations merged per stamp, MergedFeatureFrames) for a
// fault-injection replay (tools/vio_faults): the camera's side of
// dataset/fault_injection.h. Applied to merged frames, a stereo pair loses
// both its images together.
//
// A fault is placed by time: `t_s` seconds after `start_ns` (the sequence
// start), over `duration_s` seconds. Which frames and observations a fault
// picks at random is decided from the stamp, the feature id, the camera and
// `seed` alone, so equal inputs give equal outputs on every platform.
//
// A frame without observations has no row in features.csv: a frame emptied
// here disappears from the file, as it would from a tracker that found
// nothing in a black or blurred image.

#include <cstdint>
#include <string>
#include <vector>

#include "geometry/feature_observation.h"

namespace vio {

enum class FrameFaultKind {
  kBlackout,     // every frame in [t_s, t_s + duration_s) removed
  kEmptyFrames,  // a `fraction` of the frames in the span lose every feature
  kHalfRate,     // from t_s on, every second frame removed (the rate halves)
  kOutliers,     // a `fraction` of the observations of each frame in the span
                 // moved to a random pixel of the image
  kTimeOffset,   // every stamp moved by `offset_s` (an unconfigured camera-
                 // IMU time offset; t_s and duration_s unused)
};

struct FrameFault {
  FrameFaultKind kind = FrameFaultKind::kBlackout;
  double t_s = 0.0;         // where [s after start_ns]
  double duration_s = 0.0;  // span [s]; kHalfRate: 0 means to the end
  double fraction = 0.0;    // kEmptyFrames, kOutliers: share in (0, 1] [-]
  double offset_s = 0.0;    // kTimeOffset [s]
  uint32_t seed = 1;        // kEmptyFrames, kOutliers
  int width = 0;            // kOutliers: image size [px]
  int height = 0;

  // "a 2.000 s camera blackout at 4.000 s" and the like.
  std::string Describe() const;
  // True when the fields fit the kind; otherwise false and a message that
  // names the field.
  bool Validate(std::string* message) const;
};

// The frames with the fault applied. Throws std::invalid_argument when the
// fault does not Validate() or its span holds no frame.
std::vector<FeatureFrame> WithFrameFault(std::vector<FeatureFrame> frames,
                                         const FrameFault& fault,
                                         int64_t start_ns);

}  // namespace vio

#endif  // VIO_DATASET_FRAME_FAULTS_H_
