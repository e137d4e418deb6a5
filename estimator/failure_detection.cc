#include "estimator/failure_detection.h"

#include <cmath>

namespace vio {

const char* FailureName(Failure failure) {
  switch (failure) {
    case Failure::kNone:
      return "none";
    case Failure::kNonFinite:
      return "non-finite state";
    case Failure::kFewLandmarks:
      return "too few landmarks";
    case Failure::kAccelBias:
      return "implausible accelerometer bias";
    case Failure::kGyroBias:
      return "implausible gyroscope bias";
    case Failure::kPositionJump:
      return "position jump";
    case Failure::kRotationJump:
      return "rotation jump";
    case Failure::kSpeed:
      return "speed beyond the limit";
    case Failure::kUnsafeState:
      return "non-finite or exploding state before the solve";
    case Failure::kImuGap:
      return "IMU gap not bridged by vision";
  }
  return "unknown";
}

Failure DetectFailure(const StepCheck& step, const FailureOptions& options) {
  if (!step.p_after.allFinite() || !step.q_after.coeffs().allFinite() ||
      !step.v_after.allFinite() || !step.b_a.allFinite() ||
      !step.b_g.allFinite()) {
    return Failure::kNonFinite;
  }
  if (step.landmarks_in_problem < options.min_tracked_landmarks) {
    return Failure::kFewLandmarks;
  }
  if (step.b_a.norm() > options.max_accel_bias) return Failure::kAccelBias;
  if (step.b_g.norm() > options.max_gyro_bias) return Failure::kGyroBias;
  if ((step.p_after - step.p_before).norm() > options.max_position_jump_m) {
    return Failure::kPositionJump;
  }
  const double angle_deg =
      step.q_before.angularDistance(step.q_after) * 180.0 / M_PI;
  if (angle_deg > options.max_rotation_jump_deg) return Failure::kRotationJump;
  if (step.v_after.norm() > options.max_speed_m_s) return Failure::kSpeed;
  return Failure::kNone;
}

}  // namespace vio
