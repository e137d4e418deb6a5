// Every kind of bad input to the preintegration is an ImuError whose message
// names the offending stamp(s) (docs/bad_input.md).

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "preintegration/imu_preintegration.h"
#include "test/testing/expect_error.h"

namespace vio {
namespace {

using ::testing::HasSubstr;

// 200 Hz samples at rest from t = 0 to 1 s.
std::vector<ImuSample> RestSamples() {
  std::vector<ImuSample> out;
  for (int64_t t = 0; t <= 1000000000; t += 5000000) {
    ImuSample s;
    s.t_ns = t;
    s.acc = Eigen::Vector3d(0.0, 0.0, 9.81);
    out.push_back(s);
  }
  return out;
}

ImuPreintegration Preintegrate(
    int64_t t0_ns, int64_t t1_ns, const std::vector<ImuSample>& samples,
    const ImuNoise& noise = ImuNoise(),
    const PreintegrationOptions& options = PreintegrationOptions()) {
  return ImuPreintegration(t0_ns, t1_ns, samples, Eigen::Vector3d::Zero(),
                           Eigen::Vector3d::Zero(), noise, options);
}

TEST(ImuPreintegrationInput, ImuErrorIsAnInvalidArgument) {
  EXPECT_THROW(Preintegrate(0, 0, RestSamples()), std::invalid_argument);
}

TEST(ImuPreintegrationInput, RepeatedStampIsRejected) {
  std::vector<ImuSample> s = RestSamples();
  s[20].t_ns = s[19].t_ns;
  EXPECT_EQ(ErrorMessage<ImuError>([&] { Preintegrate(0, 500000000, s); }),
            "IMU sample at t = 95000000 ns does not come after the previous "
            "one (t = 95000000 ns): stamps must increase");
}

TEST(ImuPreintegrationInput, DecreasingStampIsRejectedEvenOutsideTheInterval) {
  // A disordered stream cannot be searched reliably, wherever the disorder is.
  std::vector<ImuSample> s = RestSamples();
  s[150].t_ns = s[148].t_ns - 1;
  EXPECT_THAT(ErrorMessage<ImuError>([&] { Preintegrate(0, 500000000, s); }),
              HasSubstr("IMU sample at t = 739999999 ns does not come after "
                        "the previous one (t = 745000000 ns)"));
}

TEST(ImuPreintegrationInput, NanAccelerationIsRejected) {
  std::vector<ImuSample> s = RestSamples();
  s[10].acc.y() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THAT(ErrorMessage<ImuError>([&] { Preintegrate(0, 500000000, s); }),
              HasSubstr("IMU sample at t = 50000000 ns is not finite"));
}

TEST(ImuPreintegrationInput, InfiniteRateIsRejected) {
  std::vector<ImuSample> s = RestSamples();
  s[30].gyr.z() = -std::numeric_limits<double>::infinity();
  EXPECT_THAT(ErrorMessage<ImuError>([&] { Preintegrate(0, 500000000, s); }),
              HasSubstr("IMU sample at t = 150000000 ns is not finite"));
}

TEST(ImuPreintegrationInput, GapLongerThanTheLimitIsRejected) {
  std::vector<ImuSample> s = RestSamples();
  s.erase(s.begin() + 41, s.begin() + 50);  // 200 ms .. 250 ms: a 50 ms gap
  EXPECT_EQ(ErrorMessage<ImuError>([&] { Preintegrate(0, 500000000, s); }),
            "IMU gap of 0.050000 s between t = 200000000 ns and t = "
            "250000000 ns exceeds max_sample_gap (0.020000 s)");
}

TEST(ImuPreintegrationInput, GapOutsideTheIntervalIsAccepted) {
  std::vector<ImuSample> s = RestSamples();
  s.erase(s.begin() + 161, s.begin() + 170);  // 800 .. 850 ms
  EXPECT_NO_THROW(Preintegrate(0, 500000000, s));
}

TEST(ImuPreintegrationInput, GapUpToTheConfiguredLimitIsAccepted) {
  std::vector<ImuSample> s = RestSamples();
  s.erase(s.begin() + 41, s.begin() + 50);
  PreintegrationOptions options;
  options.max_sample_gap = 0.05;
  EXPECT_NO_THROW(Preintegrate(0, 500000000, s, ImuNoise(), options));
}

TEST(ImuPreintegrationInput, IntervalStartingBeforeTheSamplesIsRejected) {
  EXPECT_EQ(ErrorMessage<ImuError>(
                [&] { Preintegrate(-1, 500000000, RestSamples()); }),
            "IMU samples span [0, 1000000000] ns and do not cover the interval "
            "[-1, 500000000] ns");
}

TEST(ImuPreintegrationInput, IntervalEndingAfterTheSamplesIsRejected) {
  EXPECT_THAT(ErrorMessage<ImuError>(
                  [&] { Preintegrate(0, 1000000001, RestSamples()); }),
              HasSubstr("do not cover the interval [0, 1000000001] ns"));
}

TEST(ImuPreintegrationInput, NoSamplesIsRejected) {
  EXPECT_EQ(ErrorMessage<ImuError>([&] { Preintegrate(0, 5, {}); }),
            "no IMU samples for the interval [0, 5] ns");
}

TEST(ImuPreintegrationInput, EmptyOrReversedIntervalIsRejected) {
  EXPECT_EQ(
      ErrorMessage<ImuError>([&] { Preintegrate(7, 7, RestSamples()); }),
      "IMU interval [7, 7] ns is empty: its end must come after its start");
  EXPECT_THAT(
      ErrorMessage<ImuError>([&] { Preintegrate(9, 3, RestSamples()); }),
      HasSubstr("IMU interval [9, 3] ns is empty"));
}

TEST(ImuPreintegrationInput, InvalidNoiseIsRejected) {
  ImuNoise noise;
  noise.gyroscope_noise_density = -0.1;
  EXPECT_THAT(ErrorMessage<ImuError>(
                  [&] { Preintegrate(0, 500000000, RestSamples(), noise); }),
              HasSubstr("ImuNoise: gyroscope_noise_density must be > 0"));
}

TEST(ImuPreintegrationInput, InvalidOptionsAreRejected) {
  PreintegrationOptions options;
  options.repropagate_gyr_bias_change = 0.0;
  EXPECT_THAT(
      ErrorMessage<ImuError>([&] {
        Preintegrate(0, 500000000, RestSamples(), ImuNoise(), options);
      }),
      HasSubstr(
          "PreintegrationOptions: repropagate_gyr_bias_change must be > 0"));
}

TEST(ImuPreintegrationInput, NonFiniteBiasesAreRejected) {
  ImuPreintegration pre = Preintegrate(0, 500000000, RestSamples());
  const Eigen::Vector3d nan =
      Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  EXPECT_EQ(ErrorMessage<ImuError>([&] { pre.Repropagate(nan, nan); }),
            "biases for the IMU interval [0, 500000000] ns are not finite");
  EXPECT_THAT(ErrorMessage<ImuError>([&] {
                pre.UpdateBiasEstimate(Eigen::Vector3d::Zero(), nan);
              }),
              HasSubstr("are not finite"));
}

TEST(ImuPreintegrationInput, MergingIntervalsThatDoNotTouchIsRejected) {
  const std::vector<ImuSample> s = RestSamples();
  EXPECT_EQ(ErrorMessage<ImuError>([&] {
              ImuPreintegration::Merge(Preintegrate(0, 300000000, s),
                                       Preintegrate(400000000, 500000000, s));
            }),
            "cannot merge IMU intervals [0, 300000000] ns and [400000000, "
            "500000000] ns: the first must end where the second starts");
}

}  // namespace
}  // namespace vio
