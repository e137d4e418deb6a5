#ifndef VIO_PREINTEGRATION_GYRO_ROTATION_H_
#define VIO_PREINTEGRATION_GYRO_ROTATION_H_

// The rotation part of the IMU preintegration alone: delta_q and its
// gyroscope-bias Jacobian d_dq_d_bg from one start stamp to many end stamps,
// in one pass over the samples.
//
// ImuPreintegration (imu_preintegration.h) propagates a 15 x 15 covariance
// and 15 x 6 bias Jacobians at every sample, and an interval per end stamp
// integrates its samples from the start again: n end stamps cost O(n^2)
// full steps. A caller that needs the attitudes alone (the gyroscope-aided
// start's parallax precheck, estimator/gyro_aided_initializer.h) gets them
// here from the rotation rows of the same discrete step (midpoint_step.h):
//   phi      = ((w_k + w_{k+1}) / 2 - b_g) dt
//   q_{k+1}  = q_k (x) Exp(phi)
//   J_{k+1}  = Exp(phi)^T J_k - Jr(phi) dt      (J = d_dq_d_bg, J_0 = 0)
// which are F's rows kImuR (d dth_{k+1} / d dth_k = dR^T, d / d b_g = -Jr dt)
// applied to d x / d b_g; the bias rows of F are the identity, so only these
// two blocks reach the rotation's bias column.
//
// Each end stamp is closed exactly as its own ImuPreintegration would close
// it: the samples strictly before it, then one step to the sample
// interpolated at the stamp, without going on from that interpolated sample
// (the pass continues from the real samples). So each result equals
// ImuPreintegration(t0_ns, t_ns, ...).result()'s delta.q and d_dq_d_bg up to
// rounding (test/gyro_rotation_test.cc).
//
// Bad input: ImuError (an std::invalid_argument) as for ImuPreintegration,
// whose checks the whole span [t0_ns, last end stamp] goes through
// (SliceImuInterval), and for end stamps out of order or not after t0_ns.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "preintegration/imu_types.h"

namespace vio {

// The rotation from t0_ns to t1_ns at linearisation bias lin_b_g.
struct GyroRotation {
  int64_t t0_ns = 0;  // [ns]
  int64_t t1_ns = 0;  // [ns]
  Eigen::Quaterniond delta_q = Eigen::Quaterniond::Identity();  // b_0 <- b_1
  Eigen::Matrix3d d_dq_d_bg = Eigen::Matrix3d::Zero();  // right tangent [s]
  Eigen::Vector3d lin_b_g = Eigen::Vector3d::Zero();    // [rad/s]

  // delta_q (x) Exp(d_dq_d_bg (b_g - lin_b_g)), normalised: the rotation of
  // PreintegratedImu::Corrected.
  Eigen::Quaterniond Corrected(const Eigen::Vector3d& b_g) const;
};

// The rotations from t0_ns to each of t1_ns (non-decreasing, each after
// t0_ns) at gyroscope bias b_g [rad/s]; `samples` as for ImuPreintegration.
// Throws ImuError on bad input (see the file comment).
std::vector<GyroRotation> IntegrateGyroRotations(
    int64_t t0_ns, const std::vector<int64_t>& t1_ns,
    const std::vector<ImuSample>& samples, const Eigen::Vector3d& b_g,
    double max_sample_gap);

}  // namespace vio

#endif  // VIO_PREINTEGRATION_GYRO_ROTATION_H_
