// Any trajectory file vio_eval takes (dataset/trajectory_io.h:
// ReadTrajectoryFile tells TUM, EuRoC CSV and KITTI apart by content), then
// paired with itself as vio_eval pairs an estimate with its ground truth
// (eval/association.h): every pose must find a partner at its own stamp (or
// line). Any refusal is a DatasetError naming the file.

#include <cstddef>
#include <cstdint>

#include "dataset/csv.h"
#include "dataset/trajectory_io.h"
#include "eval/association.h"
#include "fuzz/fuzz_input.h"
#include "fuzz/trajectory_checks.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static vio::fuzz::ScratchFile file("trajectory.txt");
  const std::string& path = file.Write(data, size);
  vio::TrajectoryFile read;
  try {
    read = vio::ReadTrajectoryFile(path);
  } catch (const vio::DatasetError& e) {
    vio::fuzz::RequireNamesFile(e.what(), path);
    return 0;
  }
  vio::fuzz::RequireValidTrajectory(read.poses);
  const vio::Association a =
      read.stamped() ? vio::Associate(read.poses, read.poses, {0.0})
                     : vio::AssociateByIndex(read.poses, read.poses);
  vio::fuzz::Require(a.size() == read.poses.size(), "a pose found no partner");
  for (size_t i = 0; i < a.size(); ++i) {
    vio::fuzz::Require(a.estimate[i].t_ns == a.ground_truth[i].t_ns,
                       "a pose was paired with another stamp");
  }
  return 0;
}
