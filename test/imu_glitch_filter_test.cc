#include "preintegration/imu_glitch_filter.h"

#include <gtest/gtest.h>

#include <limits>
#include <string>
#include <vector>

namespace vio {
namespace {

constexpr int64_t kPeriodNs = 5000000;  // 200 Hz

// A good sample k of a stream whose values change linearly with k.
ImuSample Good(int k) {
  ImuSample s;
  s.t_ns = k * kPeriodNs;
  s.acc = Eigen::Vector3d(0.1 * k, -0.2, 9.81);
  s.gyr = Eigen::Vector3d(0.01 * k, 0.3, -0.05 * k);
  return s;
}

ImuSample Glitched(int k, double gyro_x) {
  ImuSample s = Good(k);
  s.gyr.x() = gyro_x;
  return s;
}

TEST(ImuRange, DefaultsAreTheAdis16448RangeAndBoundEveryAxis) {
  const ImuRange range;
  EXPECT_NEAR(range.accelerometer_range, 18.0 * 9.80665, 0.01);
  EXPECT_NEAR(range.gyroscope_range, 1000.0 * 3.14159265 / 180.0, 1e-3);
  ImuSample s;
  s.acc = Eigen::Vector3d(0.0, -176.5, 0.0);
  s.gyr = Eigen::Vector3d(0.0, 0.0, 17.45);
  EXPECT_TRUE(range.Contains(s));
  for (int axis = 0; axis < 3; ++axis) {
    ImuSample a = s, g = s;
    a.acc[axis] = 177.0;
    g.gyr[axis] = -17.5;
    EXPECT_FALSE(range.Contains(a)) << axis;
    EXPECT_FALSE(range.Contains(g)) << axis;
  }
  s.acc.x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(range.Contains(s));
}

TEST(ImuRange, ValidateNamesTheBadField) {
  ImuRange range;
  std::string message;
  EXPECT_TRUE(range.Validate(&message));
  range.gyroscope_range = 0.0;
  EXPECT_FALSE(range.Validate(&message));
  EXPECT_EQ(message, "gyroscope_range must be > 0 (got 0)");
  range = ImuRange();
  range.accelerometer_range = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(range.Validate(&message));
  EXPECT_EQ(message.rfind("accelerometer_range must be > 0", 0), 0u);
}

TEST(ImuGlitchFilter, AGlitchIsHeldThenInterpolatedFromItsNeighbours) {
  ImuGlitchFilter filter(ImuRange(), 0.02);
  std::vector<ImuSample> stream;
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(filter.Add(Good(k), &stream), ImuScreening::kAccepted);
  }
  EXPECT_EQ(filter.Add(Glitched(3, 1e308), &stream), ImuScreening::kReplaced);
  EXPECT_EQ(filter.Add(Glitched(4, -1000.0), &stream), ImuScreening::kReplaced);
  ASSERT_EQ(stream.size(), 5u);
  // Before the next good sample: the last good values, at their own stamps.
  EXPECT_EQ(stream[4].t_ns, Good(4).t_ns);
  EXPECT_EQ(stream[4].gyr, Good(2).gyr);
  EXPECT_EQ(stream[4].acc, Good(2).acc);
  EXPECT_EQ(filter.Add(Good(5), &stream), ImuScreening::kAccepted);
  // The stream is linear in k, so the interpolation restores it exactly.
  ASSERT_EQ(stream.size(), 6u);
  for (int k = 0; k < 6; ++k) {
    EXPECT_EQ(stream[k].t_ns, Good(k).t_ns);
    EXPECT_LT((stream[k].gyr - Good(k).gyr).norm(), 1e-12) << k;
    EXPECT_LT((stream[k].acc - Good(k).acc).norm(), 1e-12) << k;
  }
}

TEST(ImuGlitchFilter, GlitchesBeyondTheReplacementSpanAreDroppedLeavingAGap) {
  ImuGlitchFilter filter(ImuRange(), 0.02);  // four periods
  std::vector<ImuSample> stream;
  filter.Add(Good(0), &stream);
  for (int k = 1; k <= 4; ++k) {
    EXPECT_EQ(filter.Add(Glitched(k, 50.0), &stream), ImuScreening::kReplaced)
        << k;
  }
  for (int k = 5; k <= 9; ++k) {
    EXPECT_EQ(filter.Add(Glitched(k, 50.0), &stream), ImuScreening::kDropped)
        << k;
  }
  filter.Add(Good(10), &stream);
  ASSERT_EQ(stream.size(), 6u);
  EXPECT_EQ(stream[4].t_ns, Good(4).t_ns);
  EXPECT_EQ(stream[5].t_ns, Good(10).t_ns);
  // Interpolated between samples 0 and 10.
  EXPECT_LT((stream[4].gyr - Good(4).gyr).norm(), 1e-12);
}

TEST(ImuGlitchFilter, AGlitchBeforeAnyGoodSampleIsDropped) {
  ImuGlitchFilter filter(ImuRange(), 0.02);
  std::vector<ImuSample> stream;
  EXPECT_EQ(filter.Add(Glitched(0, 1e6), &stream), ImuScreening::kDropped);
  EXPECT_TRUE(stream.empty());
  EXPECT_EQ(filter.Add(Good(1), &stream), ImuScreening::kAccepted);
  EXPECT_EQ(stream.size(), 1u);
}

TEST(ImuGlitchFilter, SamplesErasedFromTheFrontDoNotDisturbTheReplacement) {
  ImuGlitchFilter filter(ImuRange(), 0.02);
  std::vector<ImuSample> stream;
  filter.Add(Good(0), &stream);
  filter.Add(Good(1), &stream);
  filter.Add(Glitched(2, 1e9), &stream);
  stream.erase(stream.begin(), stream.begin() + 2);  // the good ones
  filter.Add(Good(3), &stream);
  ASSERT_EQ(stream.size(), 2u);
  EXPECT_LT((stream[0].gyr - Good(2).gyr).norm(), 1e-12);
}

TEST(ImuGlitchFilter, RejectsABadRangeOrSpan) {
  ImuRange range;
  range.accelerometer_range = -1.0;
  EXPECT_THROW(ImuGlitchFilter(range, 0.02), std::invalid_argument);
  EXPECT_THROW(ImuGlitchFilter(ImuRange(), 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace vio
