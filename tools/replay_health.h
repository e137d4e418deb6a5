#ifndef VIO_TOOLS_REPLAY_HEALTH_H_
#define VIO_TOOLS_REPLAY_HEALTH_H_

// What a replay says about the bad input it survived and how much of the
// sequence it tracked (docs/robustness.md): a warning line per fault, the
// summary lines that count them, and the exit status.

#include <cstdint>
#include <string>
#include <vector>

#include "dataset/imu_stamp_filter.h"
#include "estimator/estimator.h"
#include "frontend/observation_builder.h"

namespace vio {

// Everything the input checks counted, from the reader to the estimator.
struct InputReport {
  std::string imu_file;                    // for the reader's warnings
  ImuStampReport imu_stamps;               // lines the reader dropped
  ObservationBuilderSummary observations;  // what the observation step removed
  int64_t start_ns = 0;  // the sequence start, for times in seconds
};

// One line per fault, each starting "warning: ": the reader's dropped IMU
// lines (once per kind, with the first line), samples outside the measuring
// range, each IMU gap longer than max_sample_gap with its time, length and
// what became of the frames across it, and observations outside the image.
std::vector<std::string> InputWarnings(const InputReport& input,
                                       const EstimatorSummary& summary,
                                       const ImuRange& range);

// Summary lines (two-space indent, newline-terminated): frames with a pose
// and their share, IMU input (dropped lines, replaced samples, short and
// long gaps, frames tracked on vision alone), observations removed, resets
// by cause.
std::string DescribeInputHandling(const InputReport& input,
                                  const EstimatorSummary& summary,
                                  int64_t frames_with_pose);

// When the start came so late that fewer than half of the frames were
// initialised: one line starting "warning: " with the share, the time of
// the first start after start_ns [s] and the attempts refused before it;
// otherwise "". (Such a run also ends with status 4: its frames before the
// start have no pose.)
std::string LateStartWarning(const EstimatorSummary& summary, int64_t start_ns);

// The exit status of a replay that ran to the end, and when it is not 0 the
// reason, one line:
//   0  most frames got a pose;
//   3  the estimator never initialised (the reason: each start attempt's
//      refusals counted by method and reason, DescribeNoStart);
//   4  it initialised, but most frames got no pose (the run did not track,
//      or started late).
int ReplayExitStatus(const EstimatorSummary& summary, int64_t frames_with_pose,
                     std::string* why);

}  // namespace vio

#endif  // VIO_TOOLS_REPLAY_HEALTH_H_
