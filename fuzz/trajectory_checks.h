#ifndef VIO_FUZZ_TRAJECTORY_CHECKS_H_
#define VIO_FUZZ_TRAJECTORY_CHECKS_H_

// What every trajectory reader promises of a file it accepted
// (dataset/trajectory_io.h): at least one pose, stamps that never decrease,
// finite positions, unit quaternions.

#include <cmath>

#include "dataset/trajectory.h"
#include "fuzz/fuzz_input.h"

namespace vio::fuzz {

inline void RequireValidTrajectory(const Trajectory& poses) {
  Require(!poses.empty(), "no pose and no error");
  for (size_t i = 0; i < poses.size(); ++i) {
    Require(i == 0 || poses[i].t_ns >= poses[i - 1].t_ns,
            "stamps decrease at pose " + std::to_string(i));
    Require(poses[i].p_w_b.allFinite(), "a non-finite position");
    Require(std::abs(poses[i].q_w_b.norm() - 1.0) < 1e-9,
            "a quaternion is not normalised");
  }
}

}  // namespace vio::fuzz

#endif  // VIO_FUZZ_TRAJECTORY_CHECKS_H_
