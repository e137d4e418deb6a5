#ifndef VIO_DATASET_TRAJECTORY_H_
#define VIO_DATASET_TRAJECTORY_H_

// Trajectories as plain data: what the estimator writes, what the ground truth
// holds, what the evaluation compares.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

namespace vio {

// Pose of the body (IMU) frame B in the world W at a stamp.
struct StampedPose {
  int64_t t_ns = 0;
  Eigen::Vector3d p_w_b = Eigen::Vector3d::Zero();  // [m]
  Eigen::Quaterniond q_w_b = Eigen::Quaterniond::Identity();
};

// A full navigation state, as EuRoC's ground truth and our CSV output hold it.
struct StampedState {
  int64_t t_ns = 0;
  Eigen::Vector3d p_w_b = Eigen::Vector3d::Zero();  // [m]
  Eigen::Quaterniond q_w_b = Eigen::Quaterniond::Identity();
  Eigen::Vector3d v_w = Eigen::Vector3d::Zero();  // [m/s]
  Eigen::Vector3d b_a = Eigen::Vector3d::Zero();  // [m/s^2]
  Eigen::Vector3d b_g = Eigen::Vector3d::Zero();  // [rad/s]
};

using Trajectory = std::vector<StampedPose>;

inline StampedPose PoseOf(const StampedState& s) {
  return {s.t_ns, s.p_w_b, s.q_w_b};
}

}  // namespace vio

#endif  // VIO_DATASET_TRAJECTORY_H_
