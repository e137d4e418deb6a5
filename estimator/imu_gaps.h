#ifndef VIO_ESTIMATOR_IMU_GAPS_H_
#define VIO_ESTIMATOR_IMU_GAPS_H_

// Gaps in the IMU stream, as the estimator meets them. A step between two
// samples longer than 1.5 nominal periods is a gap; up to the
// preintegration's max_sample_gap it is short, integrated across and only
// counted. A longer one cannot be integrated across: the frames whose IMU
// interval spans it are tracked on vision alone against the window's
// landmarks (estimator/visual_tracker.h), and visual-inertial estimation
// resumes with the first interval the IMU covers again; where vision cannot
// track, the frames get no pose until the IMU returns, and the window starts
// afresh there (a reset with cause kImuGap). Each long gap is logged with
// what became of it.

#include <cstdint>
#include <vector>

#include "preintegration/imu_types.h"

namespace vio {

struct ImuGap {
  int64_t t_start_ns = 0;  // the last sample before the gap [ns]
  int64_t t_end_ns = -1;   // the first sample after it; -1: none came [ns]
  int frames_visual = 0;   // frames tracked on vision alone across it
  int frames_lost = 0;     // frames given no pose (vision could not track)
  bool reset = false;      // the window started afresh after it

  bool open() const { return t_end_ns < 0; }
  // (t_end - t_start) [s]; 0 while open.
  double length_s() const {
    return open() ? 0.0 : 1e-9 * static_cast<double>(t_end_ns - t_start_ns);
  }
};

// The longest time [ns] without a sample that the preintegration of
// [t0_ns, t1_ns] would have to cross: the largest step between consecutive
// samples from the last one at or before t0_ns to the first one at or after
// t1_ns. Where the stream does not reach that far, the stretch from its
// first sample back to t0_ns or from its last sample on to t1_ns counts (the
// whole interval when the stream is empty). `imu` is sorted by stamp;
// t0_ns <= t1_ns (t0_ns == t1_ns: the samples around one instant).
int64_t LongestImuHoleNs(const std::vector<ImuSample>& imu, int64_t t0_ns,
                         int64_t t1_ns);

}  // namespace vio

#endif  // VIO_ESTIMATOR_IMU_GAPS_H_
