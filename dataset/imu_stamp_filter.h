#ifndef VIO_DATASET_IMU_STAMP_FILTER_H_
#define VIO_DATASET_IMU_STAMP_FILTER_H_

// What the IMU reader does, unless asked to be strict, with samples whose
// stamps do not strictly increase (exports from rosbags and phone or drone
// logs repeat lines and carry the odd stamp out of place):
//
//   - a line repeated exactly (same stamp, same six values) is dropped;
//   - a stamp repeated with other values: the first sample is kept, the
//     later ones are dropped;
//   - a sample whose stamp is before the last kept one is dropped (out of
//     order); so is a single sample whose stamp runs ahead of the samples
//     after it (a stamp glitch into the future), which would otherwise put
//     every sample after it out of order.
//
// Each is counted, with the first line of each kind, so that the tools can
// warn once per kind. The kept samples strictly increase.

#include <cstdint>
#include <vector>

#include "preintegration/imu_types.h"

namespace vio {

// One data line of imu0/data.csv.
struct ImuLine {
  ImuSample sample;
  int line = 0;  // 1-based line number in the file
};

struct ImuStampReport {
  int repeated_lines = 0;           // exact repeats: dropped
  int conflicting_repeats = 0;      // same stamp, other values: dropped
  int out_of_order = 0;             // stamp out of place: dropped
  int first_repeated_line = 0;      // 0: none
  int first_conflict_line = 0;      // 0: none
  int first_out_of_order_line = 0;  // 0: none
  int64_t first_conflict_t_ns = 0;  // the stamp of the first conflict [ns]

  int dropped() const {
    return repeated_lines + conflicting_repeats + out_of_order;
  }
};

// The samples of `lines` (in file order) with the stamps cleaned as the file
// comment says; the counts are added to *report.
std::vector<ImuSample> FilterImuStamps(const std::vector<ImuLine>& lines,
                                       ImuStampReport* report);

}  // namespace vio

#endif  // VIO_DATASET_IMU_STAMP_FILTER_H_
