#ifndef VIO_EVAL_POSE_INTERPOLATION_H_
#define VIO_EVAL_POSE_INTERPOLATION_H_

// The pose of a trajectory at any stamp within its span: position linear,
// attitude by slerp between the two neighbouring poses. With ground truth at
// 200 Hz this is what a camera frame between two samples needs.

#include <Eigen/Geometry>
#include <cstdint>

#include "dataset/trajectory.h"

namespace vio {

// The pose at t_ns; false when t_ns lies outside [first, last] stamp or the
// trajectory is empty. Stamps must increase (the readers guarantee it).
bool InterpolatePose(const Trajectory& trajectory, int64_t t_ns,
                     Eigen::Isometry3d* T_w_b);

}  // namespace vio

#endif  // VIO_EVAL_POSE_INTERPOLATION_H_
