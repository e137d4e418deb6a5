#include "estimator/failure_detection.h"

#include <gtest/gtest.h>

#include <limits>

#include "geometry/so3.h"

namespace vio {
namespace {

StepCheck Healthy() {
  StepCheck s;
  s.landmarks_in_problem = 100;
  s.p_before = {1.0, 2.0, 3.0};
  s.p_after = {1.05, 2.0, 3.0};
  s.q_before = ExpQuaternion(Eigen::Vector3d(0.1, 0.2, 0.3));
  s.q_after = ExpQuaternion(Eigen::Vector3d(0.11, 0.2, 0.3));
  s.b_a = {0.1, 0.0, -0.1};
  s.b_g = {0.01, 0.0, 0.02};
  return s;
}

TEST(DetectFailure, AcceptsAPlausibleStep) {
  EXPECT_EQ(DetectFailure(Healthy(), FailureOptions()), Failure::kNone);
}

TEST(DetectFailure, NamesEachBrokenRule) {
  const FailureOptions o;
  StepCheck s = Healthy();
  s.v_after.x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(DetectFailure(s, o), Failure::kNonFinite);
  s = Healthy();
  s.landmarks_in_problem = o.min_tracked_landmarks - 1;
  EXPECT_EQ(DetectFailure(s, o), Failure::kFewLandmarks);
  s = Healthy();
  s.b_a = {o.max_accel_bias + 0.1, 0, 0};
  EXPECT_EQ(DetectFailure(s, o), Failure::kAccelBias);
  s = Healthy();
  s.b_g = {0, 0, -o.max_gyro_bias - 0.01};
  EXPECT_EQ(DetectFailure(s, o), Failure::kGyroBias);
  s = Healthy();
  s.p_after = s.p_before + Eigen::Vector3d(0, o.max_position_jump_m + 0.1, 0);
  EXPECT_EQ(DetectFailure(s, o), Failure::kPositionJump);
  s = Healthy();
  s.q_after =
      s.q_before * ExpQuaternion(Eigen::Vector3d(
                       0, 0, (o.max_rotation_jump_deg + 1.0) * M_PI / 180.0));
  EXPECT_EQ(DetectFailure(s, o), Failure::kRotationJump);
  EXPECT_STREQ(FailureName(Failure::kRotationJump), "rotation jump");
  s = Healthy();
  s.v_after = {0.0, -o.max_speed_m_s - 1.0, 0.0};
  EXPECT_EQ(DetectFailure(s, o), Failure::kSpeed);
  EXPECT_STREQ(FailureName(Failure::kSpeed), "speed beyond the limit");
}

}  // namespace
}  // namespace vio
