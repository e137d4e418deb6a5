#include "config/simulator_config.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <iostream>
#include <sstream>

#include "config/yaml_reader.h"
#include "dataset/sim_trajectory.h"
#include "test/testing/expect_error.h"
#include "test/testing/temp_folder.h"

namespace vio {
namespace {

using testing::TempFolder;

std::string Preset(const std::string& name) {
  return std::string(VIO_SOURCE_DIR) + "/config/sim_" + name + ".yaml";
}

std::string ReadText(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Fastest speed [m/s] and body rate [rad/s] of a motion after its blend.
std::pair<double, double> Extremes(const SimMotionOptions& motion) {
  const SimTrajectory trajectory(motion);
  double speed = 0.0, rate = 0.0;
  const double start = motion.still_duration_s + motion.blend_duration_s;
  for (double t = start; t < start + 2.0 * motion.lap_period_s; t += 0.01) {
    const SimState s = trajectory.At(t);
    speed = std::max(speed, s.v_w.norm());
    rate = std::max(rate, s.w_b.norm());
  }
  return {speed, rate};
}

TEST(SimulatorConfig, DefaultPresetEqualsTheBuiltInDefaults) {
  EXPECT_EQ(SimulatorOptionsToYaml(LoadSimulatorOptions(Preset("default"))),
            SimulatorOptionsToYaml(SimulatorOptions()));
}

TEST(SimulatorConfig, PresetsLoadAndDoWhatTheirCommentsSay) {
  const SimulatorOptions stereo = LoadSimulatorOptions(Preset("stereo"));
  EXPECT_TRUE(stereo.camera.stereo);
  const SimulatorOptions outliers = LoadSimulatorOptions(Preset("outliers"));
  EXPECT_FALSE(outliers.camera.stereo);
  EXPECT_EQ(outliers.camera.outlier_fraction, 0.1);
  const SimulatorOptions aggressive =
      LoadSimulatorOptions(Preset("aggressive"));
  EXPECT_EQ(aggressive.camera.time_offset_s, 0.005);
  const auto [speed, rate] = Extremes(SimulatorOptions().motion);
  const auto [fast_speed, fast_rate] = Extremes(aggressive.motion);
  EXPECT_LT(speed, 1.4);  // ~1 m/s
  EXPECT_LT(rate, 1.0);
  EXPECT_GT(fast_speed, 2.5);  // ~2.9 m/s
  EXPECT_GT(fast_rate, 1.5);   // ~1.8 rad/s
  std::cout << "default: " << speed << " m/s " << rate
            << " rad/s; aggressive: " << fast_speed << " m/s " << fast_rate
            << " rad/s\n";
}

TEST(SimulatorConfig, PrintedOptionsLoadBackUnchanged) {
  SimulatorOptions options;
  options.seed = 4000000000u;
  options.duration_s = 12.345;
  options.motion.yaw_amplitude_rad = 0.1234567890123;
  options.motion.shape = SimShape::kCircle;
  options.motion.start_phase_s = 3.25;
  options.motion.attitude_rate_factor = 2.5;
  options.imu.add_noise = false;
  options.imu.initial_gyroscope_bias = {1e-3, -2e-3, 3.25e-3};
  options.camera.stereo = true;
  options.camera.time_offset_s = -0.0125;
  options.room.landmarks = 1234;
  TempFolder dir;
  dir.Write("sim.yaml", SimulatorOptionsToYaml(options));
  const SimulatorOptions back = LoadSimulatorOptions(dir.Path("sim.yaml"));
  EXPECT_EQ(SimulatorOptionsToYaml(back), SimulatorOptionsToYaml(options));
  EXPECT_EQ(back.seed, 4000000000u);
  EXPECT_EQ(back.motion.yaw_amplitude_rad, 0.1234567890123);
  EXPECT_EQ(back.motion.shape, SimShape::kCircle);
  EXPECT_EQ(back.motion.start_phase_s, 3.25);
  EXPECT_EQ(back.motion.attitude_rate_factor, 2.5);
  EXPECT_EQ(back.imu.initial_gyroscope_bias.z(), 3.25e-3);
}

TEST(SimulatorConfig, MissingWrongOrOutOfRangeKeysAreNamed) {
  TempFolder dir;
  const std::string text = ReadText(Preset("default"));
  const struct {
    std::string from, to, message;
  } cases[] = {
      {"  outlier_fraction: 0\n", "", "camera.outlier_fraction is missing"},
      {"motion:", "motions:", "sim.yaml: motion is missing"},
      {"  outlier_fraction: 0\n", "  outlier_fraction: 2\n",
       "sim.yaml: camera.outlier_fraction must be in [0, 1]"},
      {"  lap_period_s: 15", "  lap_period_s: -1",
       "sim.yaml: motion.lap_period_s must be > 0"},
      {"  gyroscope_random_walk: 1.9393e-05", "  gyroscope_random_walk: 0",
       "sim.yaml: imu.gyroscope_random_walk must be > 0"},
      {"  stereo: false", "  stereo: maybe",
       "camera.stereo must be true or false (got 'maybe')"},
      {"  initial_accelerometer_bias: [-0.018, 0.066, 0.031]",
       "  initial_accelerometer_bias: [-0.018, 0.066]",
       "imu.initial_accelerometer_bias must have 3 numbers (got 2)"},
      {"seed: 1", "seed: -3", "sim.yaml: seed must be in [0, 2^32) (got -3)"},
      {"  radius_x_m: 3", "  radius_x_m: 6.8",
       "sim.yaml: motion must stay 0.5 m inside the room"},
      {"  shape: ellipse", "  shape: spiral",
       "sim.yaml: motion.shape must be one of ellipse, rotation, line, circle "
       "(got 'spiral')"},
      {"  start_phase_s: 0", "  start_phase_s: -1",
       "sim.yaml: motion.start_phase_s must be >= 0"},
      {"  attitude_rate_factor: 1", "  attitude_rate_factor: 0",
       "sim.yaml: motion.attitude_rate_factor must be > 0"},
      {"  shape: ellipse", "  shape: line",
       "sim.yaml: motion.start_phase_s + duration_s must be <= "
       "motion.lap_period_s for the line"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.message);
    std::string altered = text;
    const size_t at = altered.find(c.from);
    ASSERT_NE(at, std::string::npos) << c.from;
    altered.replace(at, c.from.size(), c.to);
    dir.Write("sim.yaml", altered);
    ExpectErrorContaining<ConfigError>(
        [&] { LoadSimulatorOptions(dir.Path("sim.yaml")); }, c.message);
  }
}

}  // namespace
}  // namespace vio
