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
//     order); so is a single sample whose stamp runs ahead of the line after
//     it while that line fits after the last kept sample (a stamp glitch into
//     the future), which would otherwise put every sample after it out of
//     order.
//
// Each is counted, with the first line of each kind, so that the tools can
// warn once per kind. The kept samples strictly increase.
//
// The filter runs as the file is read, with a bounded look-ahead of one line:
// the verdict on line k needs only the samples kept before it and line k+1
// (the raw next line, whatever becomes of it), so it is given when line k+1
// arrives (or at the end of the file). Nothing else is held, so memory does
// not grow with the file. This is exactly the rule the filter had when it
// took the whole file at once (it never looked past line k+1 either): every
// input gives the same samples and the same counts as then
// (test/imu_stamp_filter_test.cc holds them equal on randomised glitchy
// files and on the real EuRoC IMU files). What one line of look-ahead
// cannot repair, and never could: two or more consecutive samples stamped
// ahead (a glitch of a run of lines) are kept, since each fits before the
// next, and the good samples after them are then dropped as out of order
// until the stamps pass the glitch (ImuStampFilter.ARunOfFutureStampsIsKept).
// A longer window could drop such a run instead, but would change the
// samples that files give today.

#include <cstdint>
#include <optional>

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

// The filter of the file comment, fed one line at a time in file order.
class ImuStampFilter {
 public:
  // The counts are added to *report, which must outlive the filter.
  explicit ImuStampFilter(ImuStampReport* report) : report_(report) {}

  // Takes the next line; decides the one before it. True when that one is
  // kept, then *kept is it (its stamp after every sample kept before).
  bool Add(const ImuLine& line, ImuSample* kept);

  // At the end of the file: decides the last line (nothing follows it to
  // run ahead of). True when it is kept, then *kept is it. Add may not be
  // called after this.
  bool Finish(ImuSample* kept);

 private:
  // The verdict on pending_, given the line after it (none at the end).
  bool Decide(const ImuLine* next, ImuSample* kept);

  ImuStampReport* report_;
  std::optional<ImuLine> pending_;  // read, not yet decided
  std::optional<ImuSample> last_kept_;
};

}  // namespace vio

#endif  // VIO_DATASET_IMU_STAMP_FILTER_H_
