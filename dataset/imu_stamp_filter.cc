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

bool ImuStampFilter::Add(const ImuLine& line, ImuSample* kept) {
  const bool decided = pending_.has_value() && Decide(&line, kept);
  pending_ = line;
  return decided;
}

bool ImuStampFilter::Finish(ImuSample* kept) {
  const bool decided = pending_.has_value() && Decide(nullptr, kept);
  pending_.reset();
  return decided;
}

bool ImuStampFilter::Decide(const ImuLine* next, ImuSample* kept) {
  const ImuSample& s = pending_->sample;
  const int line = pending_->line;
  if (last_kept_ && s.t_ns == last_kept_->t_ns) {
    if (SameValues(s, *last_kept_)) {
      Note(line, &report_->repeated_lines, &report_->first_repeated_line);
    } else {
      if (report_->conflicting_repeats == 0) {
        report_->first_conflict_t_ns = s.t_ns;
      }
      Note(line, &report_->conflicting_repeats, &report_->first_conflict_line);
    }
    return false;
  }
  const bool before_last = last_kept_ && s.t_ns < last_kept_->t_ns;
  // A stamp ahead of the next line, where the next one fits after the last
  // kept sample: this one is out of place, not all that follow it.
  const bool runs_ahead = next != nullptr && next->sample.t_ns < s.t_ns &&
                          (!last_kept_ || next->sample.t_ns > last_kept_->t_ns);
  if (before_last || runs_ahead) {
    Note(line, &report_->out_of_order, &report_->first_out_of_order_line);
    return false;
  }
  last_kept_ = s;
  *kept = s;
  return true;
}

}  // namespace vio
