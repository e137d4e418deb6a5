#ifndef VIO_ESTIMATOR_FAILURE_DETECTION_H_
#define VIO_ESTIMATOR_FAILURE_DETECTION_H_

// The rules that make the estimator give up and reset: too few landmarks in
// the problem, an implausible bias, a jump of the newest pose from one step to
// the next beyond the configured limits, a speed beyond the limit, or anything
// non-finite. The last two causes are the estimator's own, not a step's.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "estimator/estimator_options.h"

namespace vio {

enum class Failure {
  kNone,
  kNonFinite,     // a state holds NaN or infinity
  kFewLandmarks,  // fewer than min_tracked_landmarks in the problem
  kAccelBias,     // |b_a| > max_accel_bias
  kGyroBias,      // |b_g| > max_gyro_bias
  kPositionJump,  // |p_after - p_before| > max_position_jump_m
  kRotationJump,  // angle(q_before^-1 q_after) > max_rotation_jump_deg
  kSpeed,         // |v_after| > max_speed_m_s
  // Not from DetectFailure:
  kUnsafeState,  // before the solve: a window state non-finite or too fast
  kImuGap,       // an IMU gap vision could not bridge: started afresh after it
};

const char* FailureName(Failure failure);

// The newest frame's state before and after one step's solve.
struct StepCheck {
  int landmarks_in_problem = 0;
  Eigen::Vector3d p_before = Eigen::Vector3d::Zero();  // [m]
  Eigen::Vector3d p_after = Eigen::Vector3d::Zero();   // [m]
  Eigen::Quaterniond q_before = Eigen::Quaterniond::Identity();
  Eigen::Quaterniond q_after = Eigen::Quaterniond::Identity();
  Eigen::Vector3d v_after = Eigen::Vector3d::Zero();  // [m/s]
  Eigen::Vector3d b_a = Eigen::Vector3d::Zero();      // [m/s^2]
  Eigen::Vector3d b_g = Eigen::Vector3d::Zero();      // [rad/s]
};

// The first rule the step breaks (kNonFinite to kSpeed, checked in the order
// of the enum); kNone if none.
// "before" is the prediction (IMU propagation) of the newest frame, "after"
// the solved estimate.
Failure DetectFailure(const StepCheck& step, const FailureOptions& options);

}  // namespace vio

#endif  // VIO_ESTIMATOR_FAILURE_DETECTION_H_
