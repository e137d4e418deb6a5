#include "tools/replay_health.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace vio {
namespace {

using ::testing::HasSubstr;

// A run that started (at 1 s) and saw these frames.
EstimatorSummary Frames(int64_t frames, int64_t before_init,
                        int64_t without_imu) {
  EstimatorSummary s;
  s.starts.push_back(StartRecord());
  s.starts.back().t_ns = 2000000000;
  s.frames = frames;
  s.frames_before_init = before_init;
  s.frames_without_imu = without_imu;
  return s;
}

TEST(ReplayExitStatus, IsFourWhenMostFramesGotNoPose) {
  std::string why;
  EXPECT_EQ(ReplayExitStatus(Frames(161, 19, 0), 142, &why), 0);
  EXPECT_EQ(ReplayExitStatus(Frames(10, 0, 0), 6, &why), 0);
  EXPECT_TRUE(why.empty());
  // Half is not most.
  EXPECT_EQ(ReplayExitStatus(Frames(10, 0, 5), 5, &why), 4);
  EXPECT_EQ(ReplayExitStatus(Frames(161, 19, 131), 11, &why), 4);
  EXPECT_EQ(why,
            "most frames got no pose: 11 of 161 (6.8 %); 19 before "
            "initialisation, 131 skipped (no IMU and no visual track 131, out "
            "of order 0)");
  EXPECT_EQ(ReplayExitStatus(Frames(0, 0, 0), 0, &why), 4);
}

TEST(ReplayExitStatus, IsThreeWhenNeverInitialisedWithTheReasons) {
  EstimatorSummary s = Frames(150, 150, 0);
  s.starts.clear();
  for (int k = 0; k < 3; ++k) {
    InitAttempt a;
    a.t_ns = 1000000000 + k;
    a.method = InitMethod::kMono;
    a.reason = InitFailure::kLowImuExcitation;
    a.value = 0.02;
    a.limit = 0.25;
    s.init_attempts.push_back(a);
  }
  std::string why;
  // 3 takes precedence over 4 (no frame has a pose either way).
  EXPECT_EQ(ReplayExitStatus(s, 0, &why), 3);
  EXPECT_EQ(why, "the estimator never initialised: " +
                     DescribeInitFailures(s.init_attempts));
  EXPECT_THAT(why, HasSubstr("too little IMU excitation"));
  // No attempt at all: the frames had no IMU.
  EstimatorSummary none = Frames(20, 0, 20);
  none.starts.clear();
  EXPECT_EQ(ReplayExitStatus(none, 0, &why), 3);
  EXPECT_EQ(why,
            "the estimator never initialised: no frame was covered by the IMU "
            "(20 frames without IMU)");
}

TEST(LateStartWarning, WhenFewerThanHalfOfTheFramesInitialised) {
  // Half initialised is not fewer than half.
  EXPECT_EQ(LateStartWarning(Frames(10, 5, 0), 1000000000), "");
  EXPECT_EQ(LateStartWarning(Frames(10, 0, 0), 1000000000), "");
  EstimatorSummary late = Frames(61, 51, 0);
  InitAttempt a;
  a.method = InitMethod::kMono;
  a.reason = InitFailure::kLowParallax;
  late.init_attempts.push_back(a);
  EXPECT_EQ(LateStartWarning(late, 1000000000),
            "warning: only 10 of 61 frames initialised (16.4 %): the first "
            "start came at t = 1.000 s; refused before it: " +
                DescribeInitFailures(late.init_attempts));
  // Never initialised: the exit status speaks, not this warning.
  late.starts.clear();
  EXPECT_EQ(LateStartWarning(late, 1000000000), "");
}

TEST(InputWarnings, NameEachFaultOnce) {
  InputReport input;
  input.imu_file = "seq/mav0/imu0/data.csv";
  input.start_ns = 1000000000;
  input.imu_stamps.repeated_lines = 2;
  input.imu_stamps.first_repeated_line = 989;
  input.imu_stamps.conflicting_repeats = 1;
  input.imu_stamps.first_conflict_line = 1200;
  input.imu_stamps.first_conflict_t_ns = 6000000000;
  EstimatorSummary s;
  s.imu_replaced = 1;
  s.imu_first_glitch_t_ns = 5930000000;
  ImuGap bridged;
  bridged.t_start_ns = 5925000000;
  bridged.t_end_ns = 6430000000;
  bridged.frames_visual = 11;
  ImuGap open;
  open.t_start_ns = 8000000000;
  open.frames_lost = 3;
  s.imu_gaps = {bridged, open};
  input.observations.outside_image = 60;
  const std::vector<std::string> w = InputWarnings(input, s, ImuRange());
  ASSERT_EQ(w.size(), 6u);
  EXPECT_EQ(w[0],
            "warning: seq/mav0/imu0/data.csv:989: 2 exact repeat(s) of an IMU "
            "line dropped (the first here)");
  EXPECT_THAT(w[1], HasSubstr("data.csv:1200: timestamp 6000000000 repeated "
                              "with other values: the first sample kept"));
  EXPECT_THAT(w[2], HasSubstr("1 IMU sample(s) outside the measuring range "
                              "(+-176.52 m/s^2, +-17.453 rad/s), the first at "
                              "t = 4.930 s: 1 replaced"));
  EXPECT_EQ(w[3],
            "warning: IMU gap of 0.505 s at t = 4.925 s (5925000000 ns): 11 "
            "frame(s) tracked on vision alone");
  EXPECT_THAT(w[4], HasSubstr("IMU gap from t = 7.000 s (8000000000 ns) on: "
                              "no sample after it: 0 frame(s) tracked on "
                              "vision alone, 3 without a pose"));
  EXPECT_EQ(w[5],
            "warning: 60 observation(s) with a pixel outside the image "
            "removed");
}

TEST(DescribeInputHandling, CountsPosesGapsAndResetsByCause) {
  InputReport input;
  input.observations.outside_image = 60;
  EstimatorSummary s = Frames(161, 19, 0);
  s.frames_visual_only = 11;
  s.imu_short_gaps = 2;
  ImuGap gap;
  gap.t_end_ns = 1;
  gap.reset = true;
  ImuGap bridged;
  bridged.t_end_ns = 1;
  bridged.frames_visual = 3;
  ImuGap uncrossed;  // closed, but no frame was placed across it
  uncrossed.t_end_ns = 1;
  s.imu_gaps = {gap, bridged, uncrossed};
  s.reset_log = {{1, Failure::kImuGap},
                 {2, Failure::kFewLandmarks},
                 {3, Failure::kImuGap}};
  const std::string text = DescribeInputHandling(input, s, 142);
  EXPECT_THAT(text, HasSubstr("poses       142 of 161 frames (88.2 %); 11 "
                              "tracked on vision alone"));
  EXPECT_THAT(text, HasSubstr("2 short (integrated across); 3 long: 1 bridged "
                              "on vision, 1 ended in a restart, 0 left frames "
                              "without a pose, 1 crossed by no estimated "
                              "frame"));
  EXPECT_THAT(text, HasSubstr("60 outside the image"));
  EXPECT_THAT(text, HasSubstr("resets by cause  IMU gap not bridged by vision "
                              "2, too few landmarks 1"));
}

}  // namespace
}  // namespace vio
