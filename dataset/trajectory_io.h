#ifndef VIO_DATASET_TRAJECTORY_IO_H_
#define VIO_DATASET_TRAJECTORY_IO_H_

// Trajectory files.
//   TUM:   "t x y z qx qy qz qw" per line, t in seconds (decimal), pose of B in
//   W. EuRoC ground truth (state_groundtruth_estimate0/data.csv):
//          t[ns], p(3), q(w, x, y, z), v(3), b_g(3), b_a(3)
//   State CSV (our estimator output, same column order as EuRoC's ground truth
//          so every EuRoC tool reads it): t[ns], p, q(w,x,y,z), v, b_g, b_a.
// Readers check every line (field count, numbers, finite, unit quaternion
// within 1e-3, strictly increasing stamps) and throw DatasetError naming file
// and line.

#include <string>
#include <vector>

#include "dataset/trajectory.h"

namespace vio {

std::vector<StampedState> ReadEurocGroundTruth(const std::string& path);
Trajectory ReadTum(const std::string& path);
// Detects the format from the content: a data line with 17 or more
// comma-separated fields is EuRoC ground truth / state CSV, 8 fields TUM.
Trajectory ReadTrajectory(const std::string& path);

// Writers; throw DatasetError when the file cannot be written.
void WriteTum(const std::string& path, const Trajectory& trajectory);
void WriteStateCsv(const std::string& path,
                   const std::vector<StampedState>& states);

}  // namespace vio

#endif  // VIO_DATASET_TRAJECTORY_IO_H_
