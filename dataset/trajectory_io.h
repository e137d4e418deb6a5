#ifndef VIO_DATASET_TRAJECTORY_IO_H_
#define VIO_DATASET_TRAJECTORY_IO_H_

// Trajectory files: the formats evo reads, and the ones we write.
//   TUM:   "t x y z qx qy qz qw" per line (white space; commas also read), t
//          in seconds, decimal or scientific (1.403715529112143517e+09, as
//          numpy and so evo write it), pose of B in W.
//   EuRoC CSV: "t[ns], p(3), q(w, x, y, z)" and optionally more numeric
//          columns, comma-separated: the ground truth
//          (state_groundtruth_estimate0/data.csv: + v(3), b_g(3), b_a(3)),
//          our state CSV (same 17 columns, so every EuRoC tool reads it), and
//          pose-only CSVs (8 columns), as evo's `euroc` mode reads them.
//   KITTI: 12 numbers per line, the pose's 3x4 [R | t] row-major; no stamps
//          (evo's `kitti` mode pairs two such files line by line).
// Lines starting with '#' and blank lines are skipped wherever they are; a
// UTF-8 byte-order mark at the start is skipped. Readers check every line
// (field count, numbers, finite, unit quaternion or rotation within 1e-3,
// stamps never decreasing) and throw DatasetError naming the file and line.
//
// Repeated stamps: the trajectory readers below keep a pose whose stamp equals
// the previous one (TUM ground truth holds such pairs; evo keeps them too);
// eval/association.h says how they are paired. The dataset's ground truth
// (ReadEurocGroundTruth) must have strictly increasing stamps: its users
// interpolate in time.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "dataset/trajectory.h"

namespace vio {

enum class TrajectoryFormat { kTum, kEuroc, kKitti };

// "TUM", "EuRoC CSV", "KITTI".
const char* TrajectoryFormatName(TrajectoryFormat format);

// A trajectory file as read, with its format.
struct TrajectoryFile {
  TrajectoryFormat format = TrajectoryFormat::kTum;
  // For KITTI, which has no stamps, pose i gets t_ns = i * 1e9 (its line
  // index in seconds) so that the order and a plot's axis keep a meaning;
  // pair such files by index (AssociateByIndex), never by stamp.
  Trajectory poses;

  bool stamped() const { return format != TrajectoryFormat::kKitti; }
};

// The dataset's ground truth: 17 or more comma-separated fields (t[ns], p,
// q(w,x,y,z), v, b_g, b_a), stamps strictly increasing, at least one line.
std::vector<StampedState> ReadEurocGroundTruth(const std::string& path);

// The same file with the same checks, a state at a time: each is handed to
// `take` in file order once its line is checked, and none is kept, so that
// a caller can keep only the states it needs. Returns how many there were.
int64_t ForEachEurocGroundTruth(
    const std::string& path,
    const std::function<void(const StampedState&)>& take);

// The single formats, repeated stamps kept; each holds at least one pose.
Trajectory ReadTum(const std::string& path);
Trajectory ReadEurocPoses(const std::string& path);
Trajectory ReadKitti(const std::string& path);

// Tells the format from the first data line and reads the file:
//   commas, 8 or more fields, an integer first field (ns):  EuRoC CSV
//   exactly 8 fields otherwise:                              TUM
//   12 fields separated by white space:                      KITTI
// Anything else is a DatasetError saying what was found.
TrajectoryFile ReadTrajectoryFile(const std::string& path);

// The same for callers that need stamps: a KITTI file is a DatasetError.
Trajectory ReadTrajectory(const std::string& path);

// Writers; throw DatasetError when the file cannot be written.
void WriteTum(const std::string& path, const Trajectory& trajectory);
void WriteStateCsv(const std::string& path,
                   const std::vector<StampedState>& states);
// 12 values per line with 9 significant digits, as KITTI's own files; the
// stamps are not written.
void WriteKitti(const std::string& path, const Trajectory& trajectory);

}  // namespace vio

#endif  // VIO_DATASET_TRAJECTORY_IO_H_
