#include "tools/replay_health.h"

#include <cstdarg>
#include <cstdio>
#include <map>
#include <sstream>

namespace vio {
namespace {

std::string Format(const char* format, ...)
    __attribute__((format(printf, 1, 2)));

std::string Format(const char* format, ...) {
  char buffer[512];
  va_list args;
  va_start(args, format);
  std::vsnprintf(buffer, sizeof(buffer), format, args);
  va_end(args);
  return buffer;
}

double Seconds(int64_t t_ns, int64_t start_ns) {
  return 1e-9 * static_cast<double>(t_ns - start_ns);
}

double Percent(int64_t part, int64_t whole) {
  return whole > 0 ? 100.0 * static_cast<double>(part) / whole : 0.0;
}

std::string GapWarning(const ImuGap& gap, int64_t start_ns) {
  std::string line =
      gap.open()
          ? Format(
                "warning: IMU gap from t = %.3f s (%lld ns) on: no sample "
                "after it",
                Seconds(gap.t_start_ns, start_ns),
                static_cast<long long>(gap.t_start_ns))
          : Format("warning: IMU gap of %.3f s at t = %.3f s (%lld ns)",
                   gap.length_s(), Seconds(gap.t_start_ns, start_ns),
                   static_cast<long long>(gap.t_start_ns));
  line += Format(": %d frame(s) tracked on vision alone", gap.frames_visual);
  if (gap.frames_lost > 0) {
    line += Format(", %d without a pose", gap.frames_lost);
  }
  if (gap.reset) line += "; the window restarted after it";
  return line;
}

}  // namespace

std::vector<std::string> InputWarnings(const InputReport& input,
                                       const EstimatorSummary& summary,
                                       const ImuRange& range) {
  std::vector<std::string> out;
  const ImuStampReport& r = input.imu_stamps;
  const char* file = input.imu_file.c_str();
  if (r.repeated_lines > 0) {
    out.push_back(
        Format("warning: %s:%d: %d exact repeat(s) of an IMU line "
               "dropped (the first here)",
               file, r.first_repeated_line, r.repeated_lines));
  }
  if (r.conflicting_repeats > 0) {
    out.push_back(Format(
        "warning: %s:%d: timestamp %lld repeated with other values: the "
        "first sample kept (%d such line(s) dropped)",
        file, r.first_conflict_line,
        static_cast<long long>(r.first_conflict_t_ns), r.conflicting_repeats));
  }
  if (r.out_of_order > 0) {
    out.push_back(
        Format("warning: %s:%d: %d IMU sample(s) out of order "
               "dropped (the first here)",
               file, r.first_out_of_order_line, r.out_of_order));
  }
  if (summary.imu_replaced + summary.imu_dropped > 0) {
    out.push_back(Format(
        "warning: %lld IMU sample(s) outside the measuring range (+-%g m/s^2, "
        "+-%g rad/s), the first at t = %.3f s: %lld replaced from their "
        "neighbours, %lld dropped",
        static_cast<long long>(summary.imu_replaced + summary.imu_dropped),
        range.accelerometer_range, range.gyroscope_range,
        Seconds(summary.imu_first_glitch_t_ns, input.start_ns),
        static_cast<long long>(summary.imu_replaced),
        static_cast<long long>(summary.imu_dropped)));
  }
  for (const ImuGap& gap : summary.imu_gaps) {
    out.push_back(GapWarning(gap, input.start_ns));
  }
  if (input.observations.outside_image > 0) {
    out.push_back(
        Format("warning: %lld observation(s) with a pixel outside the image "
               "removed",
               static_cast<long long>(input.observations.outside_image)));
  }
  return out;
}

std::string DescribeInputHandling(const InputReport& input,
                                  const EstimatorSummary& s,
                                  int64_t frames_with_pose) {
  std::ostringstream out;
  out << Format(
      "  poses       %lld of %lld frames (%.1f %%); %lld tracked on "
      "vision alone\n",
      static_cast<long long>(frames_with_pose),
      static_cast<long long>(s.frames), Percent(frames_with_pose, s.frames),
      static_cast<long long>(s.frames_visual_only));
  // Bridged means at least one frame across the gap was placed on vision;
  // a gap no estimated frame crossed (before the start, say) is not.
  int64_t bridged = 0, lost = 0, restarted = 0, uncrossed = 0;
  for (const ImuGap& gap : s.imu_gaps) {
    ++(gap.reset              ? restarted
       : gap.frames_lost > 0  ? lost
       : gap.frames_visual > 0 ? bridged
                               : uncrossed);
  }
  out << Format(
      "  imu input   %d line(s) dropped by the reader (%d repeated, %d "
      "repeated stamp, %d out of order); %lld sample(s) outside the range "
      "replaced, %lld dropped\n",
      input.imu_stamps.dropped(), input.imu_stamps.repeated_lines,
      input.imu_stamps.conflicting_repeats, input.imu_stamps.out_of_order,
      static_cast<long long>(s.imu_replaced),
      static_cast<long long>(s.imu_dropped));
  out << Format(
      "  imu gaps    %lld short (integrated across); %zu long: %lld bridged "
      "on vision, %lld ended in a restart, %lld left frames without a "
      "pose, %lld crossed by no estimated frame\n",
      static_cast<long long>(s.imu_short_gaps), s.imu_gaps.size(),
      static_cast<long long>(bridged), static_cast<long long>(restarted),
      static_cast<long long>(lost), static_cast<long long>(uncrossed));
  out << Format(
      "  observations removed: %lld outside the image, %lld not "
      "undistortable, %lld of an unknown camera\n",
      static_cast<long long>(input.observations.outside_image),
      static_cast<long long>(input.observations.failed_undistortion),
      static_cast<long long>(input.observations.unknown_camera));
  std::map<std::string, int> causes;
  for (const ResetEvent& e : s.reset_log) ++causes[FailureName(e.reason)];
  out << "  resets by cause  ";
  if (causes.empty()) out << "none";
  const char* separator = "";
  for (const auto& [name, count] : causes) {
    out << separator << name << " " << count;
    separator = ", ";
  }
  out << "\n";
  return out.str();
}

std::string LateStartWarning(const EstimatorSummary& s, int64_t start_ns) {
  const int64_t initialised = s.frames - s.frames_before_init;
  if (s.starts.empty() || 2 * initialised >= s.frames) return "";
  std::string line = Format(
      "warning: only %lld of %lld frames initialised (%.1f %%): the first "
      "start came at t = %.3f s",
      static_cast<long long>(initialised), static_cast<long long>(s.frames),
      Percent(initialised, s.frames),
      1e-9 * static_cast<double>(s.starts.front().t_ns - start_ns));
  if (!s.init_attempts.empty()) {
    line += "; refused before it: " + DescribeInitFailures(s.init_attempts);
  }
  return line;
}

int ReplayExitStatus(const EstimatorSummary& summary, int64_t frames_with_pose,
                     std::string* why) {
  if (summary.starts.empty()) {
    *why = "the estimator never initialised: " + DescribeNoStart(summary);
    return 3;
  }
  if (2 * frames_with_pose > summary.frames) return 0;
  *why = Format(
      "most frames got no pose: %lld of %lld (%.1f %%); %lld before "
      "initialisation, %lld skipped (no IMU and no visual track %lld, out of "
      "order %lld)",
      static_cast<long long>(frames_with_pose),
      static_cast<long long>(summary.frames),
      Percent(frames_with_pose, summary.frames),
      static_cast<long long>(summary.frames_before_init),
      static_cast<long long>(summary.frames_without_imu +
                             summary.frames_out_of_order),
      static_cast<long long>(summary.frames_without_imu),
      static_cast<long long>(summary.frames_out_of_order));
  return 4;
}

}  // namespace vio
