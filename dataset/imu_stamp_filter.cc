#include "dataset/imu_stamp_filter.h"

namespace vio {
namespace {

bool SameValues(const ImuSample& a, const ImuSample& b) {
  return a.acc == b.acc && a.gyr == b.gyr;
}

void Note(int line, int* count, int* first) {
  if (*count == 0) *first = line;
  ++*count;
}

}  // namespace

std::vector<ImuSample> FilterImuStamps(const std::vector<ImuLine>& lines,
                                       ImuStampReport* report) {
  std::vector<ImuSample> kept;
  kept.reserve(lines.size());
  for (size_t k = 0; k < lines.size(); ++k) {
    const ImuSample& s = lines[k].sample;
    const int line = lines[k].line;
    if (!kept.empty() && s.t_ns == kept.back().t_ns) {
      if (SameValues(s, kept.back())) {
        Note(line, &report->repeated_lines, &report->first_repeated_line);
      } else {
        if (report->conflicting_repeats == 0) {
          report->first_conflict_t_ns = s.t_ns;
        }
        Note(line, &report->conflicting_repeats, &report->first_conflict_line);
      }
      continue;
    }
    const bool before_last = !kept.empty() && s.t_ns < kept.back().t_ns;
    // A stamp ahead of the next sample, where the next one fits after the
    // last kept sample: this one is out of place, not all that follow it.
    const bool runs_ahead =
        k + 1 < lines.size() && lines[k + 1].sample.t_ns < s.t_ns &&
        (kept.empty() || lines[k + 1].sample.t_ns > kept.back().t_ns);
    if (before_last || runs_ahead) {
      Note(line, &report->out_of_order, &report->first_out_of_order_line);
      continue;
    }
    kept.push_back(s);
  }
  return kept;
}

}  // namespace vio
