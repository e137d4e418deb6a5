#include "estimator/imu_gaps.h"

#include <gtest/gtest.h>

#include <vector>

namespace vio {
namespace {

// Samples every 5 ms from 0 to 100 ms, with 30..70 ms missing (a 40 ms gap
// between 25 and 75 ms).
std::vector<ImuSample> Stream() {
  std::vector<ImuSample> imu;
  for (int64_t t = 0; t <= 100; t += 5) {
    if (t > 25 && t < 75) continue;
    ImuSample s;
    s.t_ns = t * 1000000;
    imu.push_back(s);
  }
  return imu;
}

constexpr int64_t kMs = 1000000;

TEST(LongestImuHole, IsTheLargestStepTheIntervalMustCross) {
  const std::vector<ImuSample> imu = Stream();
  EXPECT_EQ(LongestImuHoleNs(imu, 0, 20 * kMs), 5 * kMs);
  EXPECT_EQ(LongestImuHoleNs(imu, 2 * kMs, 23 * kMs), 5 * kMs);
  // Any interval reaching into the gap crosses all of it.
  EXPECT_EQ(LongestImuHoleNs(imu, 10 * kMs, 30 * kMs), 50 * kMs);
  EXPECT_EQ(LongestImuHoleNs(imu, 40 * kMs, 60 * kMs), 50 * kMs);
  EXPECT_EQ(LongestImuHoleNs(imu, 74 * kMs, 90 * kMs), 50 * kMs);
  EXPECT_EQ(LongestImuHoleNs(imu, 75 * kMs, 90 * kMs), 5 * kMs);
  // One instant: the samples around it.
  EXPECT_EQ(LongestImuHoleNs(imu, 50 * kMs, 50 * kMs), 50 * kMs);
  EXPECT_EQ(LongestImuHoleNs(imu, 80 * kMs, 80 * kMs), 0);
  EXPECT_EQ(LongestImuHoleNs(imu, 82 * kMs, 82 * kMs), 5 * kMs);
}

TEST(LongestImuHole, CountsTheStretchBeyondTheStreamsEnds) {
  const std::vector<ImuSample> imu = Stream();
  EXPECT_EQ(LongestImuHoleNs(imu, 90 * kMs, 130 * kMs), 30 * kMs);
  EXPECT_EQ(LongestImuHoleNs(imu, -20 * kMs, 10 * kMs), 20 * kMs);
  EXPECT_EQ(LongestImuHoleNs({}, 10 * kMs, 30 * kMs), 20 * kMs);
}

TEST(ImuGap, LengthIsZeroWhileOpen) {
  ImuGap gap;
  gap.t_start_ns = 100 * kMs;
  EXPECT_TRUE(gap.open());
  EXPECT_EQ(gap.length_s(), 0.0);
  gap.t_end_ns = 600 * kMs;
  EXPECT_FALSE(gap.open());
  EXPECT_DOUBLE_EQ(gap.length_s(), 0.5);
}

}  // namespace
}  // namespace vio
