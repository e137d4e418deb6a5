#ifndef VIO_TEST_TESTING_WHOLE_FILE_IMU_STAMP_FILTER_H_
#define VIO_TEST_TESTING_WHOLE_FILE_IMU_STAMP_FILTER_H_

// The IMU stamp filter as it was when the reader took imu0/data.csv whole
// (dataset/imu_stamp_filter.cc at c907eda, FilterImuStamps, unchanged but
// for its name): the reference that the bounded, line-at-a-time
// ImuStampFilter and ImuCsvStream are held equal to.

#include <vector>

#include "dataset/imu_stamp_filter.h"

namespace vio {
namespace testing {

inline std::vector<ImuSample> WholeFileImuStampFilter(
    const std::vector<ImuLine>& lines, ImuStampReport* report) {
  auto same_values = [](const ImuSample& a, const ImuSample& b) {
    return a.acc == b.acc && a.gyr == b.gyr;
  };
  auto note = [](int line, int* count, int* first) {
    if (*count == 0) *first = line;
    ++*count;
  };
  std::vector<ImuSample> kept;
  kept.reserve(lines.size());
  for (size_t k = 0; k < lines.size(); ++k) {
    const ImuSample& s = lines[k].sample;
    const int line = lines[k].line;
    if (!kept.empty() && s.t_ns == kept.back().t_ns) {
      if (same_values(s, kept.back())) {
        note(line, &report->repeated_lines, &report->first_repeated_line);
      } else {
        if (report->conflicting_repeats == 0) {
          report->first_conflict_t_ns = s.t_ns;
        }
        note(line, &report->conflicting_repeats, &report->first_conflict_line);
      }
      continue;
    }
    const bool before_last = !kept.empty() && s.t_ns < kept.back().t_ns;
    const bool runs_ahead =
        k + 1 < lines.size() && lines[k + 1].sample.t_ns < s.t_ns &&
        (kept.empty() || lines[k + 1].sample.t_ns > kept.back().t_ns);
    if (before_last || runs_ahead) {
      note(line, &report->out_of_order, &report->first_out_of_order_line);
      continue;
    }
    kept.push_back(s);
  }
  return kept;
}

}  // namespace testing
}  // namespace vio

#endif  // VIO_TEST_TESTING_WHOLE_FILE_IMU_STAMP_FILTER_H_
