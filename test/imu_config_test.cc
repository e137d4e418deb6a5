#include "config/imu_config.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

namespace vio {
namespace {

using ::testing::HasSubstr;

const char kBlock[] = R"(
imu:
  noise_from: config
  rate_hz: 200
  accelerometer_noise_density: 2.0e-3
  gyroscope_noise_density: 1.6968e-4
  accelerometer_random_walk: 3.0e-3
  gyroscope_random_walk: 1.9393e-5
  adapt_noise: false
  gravity_magnitude: 9.81
  max_sample_gap: 0.02
  repropagate_acc_bias_change: 0.1
  repropagate_gyr_bias_change: 0.01
  accelerometer_range: 176.52
  gyroscope_range: 17.453
)";

// kBlock with `key`'s line replaced by "key: value" (or removed when value
// is empty).
std::string With(const std::string& key, const std::string& value) {
  std::string text = kBlock;
  const size_t begin = text.find("  " + key + ":");
  const size_t end = text.find('\n', begin);
  text.replace(begin, end - begin + 1,
               value.empty() ? "" : "  " + key + ": " + value + "\n");
  return text;
}

std::string ErrorOf(const std::string& text) {
  try {
    LoadImuConfig(YamlNode::LoadString(text, "mem.yaml"));
  } catch (const ConfigError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no ConfigError";
  return "";
}

TEST(ImuConfig, DefaultYamlHoldsEurocAdis16448Values) {
  const ImuConfig c = LoadImuConfig(
      YamlNode::LoadFile(std::string(VIO_SOURCE_DIR) + "/config/default.yaml"));
  // EuRoC mav0/imu0/sensor.yaml (shared/data/euroc_MH_05_imu_gt), the white
  // noise 15 (accelerometer) and 2 (gyroscope) times the datasheet's for the
  // flying MAV with the landmarks kept as world points (issue 11).
  EXPECT_DOUBLE_EQ(c.noise.accelerometer_noise_density, 3.0e-2);
  EXPECT_DOUBLE_EQ(c.noise.gyroscope_noise_density, 3.3936e-4);
  EXPECT_DOUBLE_EQ(c.noise.accelerometer_random_walk, 3.0e-3);
  EXPECT_DOUBLE_EQ(c.noise.gyroscope_random_walk, 1.9393e-5);
  EXPECT_DOUBLE_EQ(c.rate_hz, 200.0);
  EXPECT_DOUBLE_EQ(c.gravity_magnitude, 9.81);
  EXPECT_DOUBLE_EQ(c.preintegration.max_sample_gap, 0.02);
  EXPECT_DOUBLE_EQ(c.preintegration.repropagate_acc_bias_change, 0.1);
  EXPECT_DOUBLE_EQ(c.preintegration.repropagate_gyr_bias_change, 0.01);
  // ADIS16448 datasheet: +-18 g, +-1000 deg/s; the built-in defaults too.
  EXPECT_DOUBLE_EQ(c.range.accelerometer_range, 176.52);
  EXPECT_DOUBLE_EQ(c.range.gyroscope_range, 17.453);
  EXPECT_EQ(c.range.accelerometer_range, ImuRange().accelerometer_range);
  EXPECT_EQ(c.range.gyroscope_range, ImuRange().gyroscope_range);
  EXPECT_EQ(c.noise_from, ImuNoiseSource::kConfig);
  // The built-in defaults (vio_replay without --config) are the file's.
  const ImuConfig built_in;
  EXPECT_EQ(c.noise.accelerometer_noise_density,
            built_in.noise.accelerometer_noise_density);
  EXPECT_EQ(c.noise.gyroscope_noise_density,
            built_in.noise.gyroscope_noise_density);
  EXPECT_EQ(c.noise.accelerometer_random_walk,
            built_in.noise.accelerometer_random_walk);
  EXPECT_EQ(c.noise.gyroscope_random_walk,
            built_in.noise.gyroscope_random_walk);
}

TEST(ImuConfig, NoiseCanComeFromTheSequence) {
  const ImuConfig c = LoadImuConfig(
      YamlNode::LoadString(With("noise_from", "sequence"), "mem.yaml"));
  EXPECT_EQ(c.noise_from, ImuNoiseSource::kSequence);
  EXPECT_STREQ(ImuNoiseSourceName(c.noise_from), "sequence");
}

TEST(ImuConfig, UnknownNoiseSourceNamesFileAndKey) {
  EXPECT_EQ(ErrorOf(With("noise_from", "datasheet")),
            "mem.yaml: imu.noise_from must be config or sequence (got "
            "'datasheet')");
  EXPECT_EQ(ErrorOf(With("noise_from", "")),
            "mem.yaml: imu.noise_from is missing");
}

TEST(ImuConfig, NonPositiveMeasuringRangeNamesFileAndKey) {
  EXPECT_EQ(ErrorOf(With("gyroscope_range", "0")),
            "mem.yaml: imu.gyroscope_range must be > 0 (got 0)");
  EXPECT_EQ(ErrorOf(With("accelerometer_range", "")),
            "mem.yaml: imu.accelerometer_range is missing");
}

TEST(ImuConfig, ApplyImuConfigCopiesGravityRateAndRange) {
  ImuConfig imu;
  imu.gravity_magnitude = 9.79;
  imu.rate_hz = 400.0;
  imu.range.accelerometer_range = 80.0;
  imu.range.gyroscope_range = 8.0;
  EstimatorOptions options;
  ApplyImuConfig(imu, &options);
  EXPECT_EQ(options.gravity_magnitude, 9.79);
  EXPECT_EQ(options.imu_stream.rate_hz, 400.0);
  EXPECT_EQ(options.imu_stream.range.accelerometer_range, 80.0);
  EXPECT_EQ(options.imu_stream.range.gyroscope_range, 8.0);
}

TEST(ImuConfig, NegativeNoiseDensityNamesFileAndKey) {
  EXPECT_EQ(ErrorOf(With("gyroscope_noise_density", "-0.1")),
            "mem.yaml: imu.gyroscope_noise_density must be > 0 (got "
            "-0.100000)");
}

TEST(ImuConfig, ZeroRandomWalkIsRejected) {
  EXPECT_THAT(ErrorOf(With("accelerometer_random_walk", "0")),
              HasSubstr("mem.yaml: imu.accelerometer_random_walk must be > 0"));
}

TEST(ImuConfig, ZeroRateIsRejected) {
  EXPECT_EQ(ErrorOf(With("rate_hz", "0")),
            "mem.yaml: imu.rate_hz must be > 0 (got 0)");
}

TEST(ImuConfig, GravityOutsideEarthsRangeIsRejected) {
  EXPECT_EQ(ErrorOf(With("gravity_magnitude", "98.1")),
            "mem.yaml: imu.gravity_magnitude must be in [9.7, 9.9] m/s^2 (got "
            "98.1)");
}

TEST(ImuConfig, GapLimitBelowOneSamplePeriodIsRejected) {
  EXPECT_EQ(ErrorOf(With("max_sample_gap", "0.001")),
            "mem.yaml: imu.max_sample_gap must be at least one sample period "
            "1 / rate_hz = 0.005 s (got 0.001)");
}

TEST(ImuConfig, NonPositiveRepropagationThresholdIsRejected) {
  EXPECT_THAT(ErrorOf(With("repropagate_gyr_bias_change", "-1")),
              HasSubstr("imu.repropagate_gyr_bias_change must be > 0"));
}

TEST(ImuConfig, MissingKeyIsAnError) {
  EXPECT_EQ(ErrorOf(With("gravity_magnitude", "")),
            "mem.yaml: imu.gravity_magnitude is missing");
}

TEST(ImuConfig, WrongTypeIsAnError) {
  EXPECT_EQ(ErrorOf(With("max_sample_gap", "soon")),
            "mem.yaml: imu.max_sample_gap must be a number (got 'soon')");
}

TEST(ImuConfig, MissingBlockIsAnError) {
  EXPECT_EQ(ErrorOf("camera: {}\n"), "mem.yaml: imu is missing");
}

}  // namespace
}  // namespace vio
