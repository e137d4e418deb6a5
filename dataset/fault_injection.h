#ifndef VIO_DATASET_FAULT_INJECTION_H_
#define VIO_DATASET_FAULT_INJECTION_H_

// Faults of the kinds recorded data carries (rosbag exports, phone and drone
// logs), applied to a sequence on purpose: to the IMU stream in memory or to
// an imu0/data.csv file, and to the pixels of a camera frame. The regression
// tests of docs/robustness.md use them; so can a fault-injection replay.
//
// A fault is placed by time: `t_s` seconds after the first IMU sample (or
// the first frame), and applies from the first sample (frame) at or after
// that time.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "geometry/feature_observation.h"
#include "preintegration/imu_types.h"

namespace vio {

enum class ImuFaultKind {
  kDrop,        // `count` samples missing (a gap)
  kGyroValue,   // gyroscope x of `count` samples set to `value` [rad/s]
  kAccelValue,  // accelerometer x of `count` samples set to `value` [m/s^2]
  kRepeat,      // one sample (line) repeated exactly, right after itself
  kBackwards,   // one sample moved `count` places later: out of order
};

struct ImuFault {
  ImuFaultKind kind = ImuFaultKind::kDrop;
  double t_s = 0.0;    // where [s after the first sample]
  int count = 1;       // samples affected [-]
  double value = 0.0;  // kGyroValue [rad/s], kAccelValue [m/s^2]

  // "5 IMU samples dropped at 4.900 s" and the like.
  std::string Describe() const;
};

// The stream with the fault applied. Throws std::invalid_argument when the
// fault does not fit (t_s beyond the stream, count < 1, count samples not
// there).
std::vector<ImuSample> WithImuFault(std::vector<ImuSample> imu,
                                    const ImuFault& fault);

// The same fault applied to the data lines of an imu0/data.csv text (the
// header and comment lines kept, values of changed lines rewritten with 17
// significant digits). Throws std::invalid_argument as WithImuFault, and
// when a data line does not start with an integer stamp.
std::string WithImuFaultInCsv(const std::string& csv_text,
                              const ImuFault& fault);

// Sets the pixel of up to `count` observations of the first frame at or after
// `t_s` (seconds after the first frame) to `uv` [px], as a corrupted
// features.csv line would hold it. Throws std::invalid_argument when there
// is no such frame.
void SetObservationPixels(std::vector<FeatureFrame>* frames, double t_s,
                          int count, const Eigen::Vector2d& uv);

}  // namespace vio

#endif  // VIO_DATASET_FAULT_INJECTION_H_
