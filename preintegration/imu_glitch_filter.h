#ifndef VIO_PREINTEGRATION_IMU_GLITCH_FILTER_H_
#define VIO_PREINTEGRATION_IMU_GLITCH_FILTER_H_

// The sensor's measuring range, and what becomes of a sample outside it.
//
// No IMU reports beyond its range: a value outside it (1e6 m/s^2, 1000 rad/s,
// 1e308 from a corrupted log line) is a glitch, and one glitched sample
// integrated into the preintegration bends every state after it (5 ms of
// 1e6 m/s^2 is 5 km/s of velocity). The filter replaces such a sample from
// its neighbours, keeping its stamp:
//   - at once by the last good sample's values (the next good one has not
//     arrived; a frame at that stamp may need the sample now);
//   - when the next good sample arrives, every replaced sample since the last
//     good one is re-set to the linear interpolation between the two.
// A run of glitches lasting longer than max_replaced_s is not papered over:
// the samples beyond it are dropped, leaving a gap in the stream for the
// caller's gap handling.

#include <cstdint>
#include <string>
#include <vector>

#include "preintegration/imu_types.h"

namespace vio {

// The largest magnitude, per axis, the sensor reports. Defaults: EuRoC's
// ADIS16448, +-18 g and +-1000 deg/s.
struct ImuRange {
  double accelerometer_range = 176.52;  // 18 g [m/s^2]
  double gyroscope_range = 17.453;      // 1000 deg/s [rad/s]

  // True when both are finite and > 0; otherwise false with a message that
  // starts with the offending field's name.
  bool Validate(std::string* message) const;

  // True when every value of the sample is finite and within the range.
  bool Contains(const ImuSample& sample) const;
};

enum class ImuScreening {
  kAccepted,  // within the range: appended as it is
  kReplaced,  // a glitch: appended with values from its neighbours
  kDropped,   // a glitch with no good neighbour close enough: not appended
};

class ImuGlitchFilter {
 public:
  // max_replaced_s: how long after the last good sample glitches are still
  // replaced [s] (the estimator passes the preintegration's max_sample_gap,
  // the longest gap integrated across). Throws std::invalid_argument when the
  // range does not validate or max_replaced_s is not > 0.
  ImuGlitchFilter(const ImuRange& range, double max_replaced_s);

  // Appends `sample` to *stream as the file comment says. The caller keeps
  // the stream's stamps increasing (sample after stream->back()) and may
  // erase samples from its front, never from its back.
  ImuScreening Add(const ImuSample& sample, std::vector<ImuSample>* stream);

  const ImuRange& range() const { return range_; }

 private:
  ImuRange range_;
  int64_t max_replaced_ns_;
  bool have_good_ = false;
  ImuSample last_good_;
};

}  // namespace vio

#endif  // VIO_PREINTEGRATION_IMU_GLITCH_FILTER_H_
