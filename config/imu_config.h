#ifndef VIO_CONFIG_IMU_CONFIG_H_
#define VIO_CONFIG_IMU_CONFIG_H_

// The `imu:` block of a configuration file (config/default.yaml):
//
//   imu:
//     rate_hz: 200                          # nominal sample rate [Hz]
//     accelerometer_noise_density: 2.0e-3   # [m/s^2/sqrt(Hz)]   (Kalibr names
//     gyroscope_noise_density: 1.6968e-4    # [rad/s/sqrt(Hz)]    and units,
//     accelerometer_random_walk: 3.0e-3     # [m/s^3/sqrt(Hz)]    as in EuRoC's
//     gyroscope_random_walk: 1.9393e-5      # [rad/s^2/sqrt(Hz)]  sensor.yaml)
//     gravity_magnitude: 9.81               # [m/s^2]
//     max_sample_gap: 0.02                  # [s]
//     repropagate_acc_bias_change: 0.1      # [m/s^2]
//     repropagate_gyr_bias_change: 0.01     # [rad/s]
//     accelerometer_range: 176.52           # per axis [m/s^2]
//     gyroscope_range: 17.453               # per axis [rad/s]
//
// Every key is required. A missing key, a wrong type or an out-of-range value
// is a ConfigError naming the file and the key, e.g.
//   "config/default.yaml: imu.gyroscope_noise_density must be > 0 (got -0.1)".

#include <string>

#include "config/yaml_reader.h"
#include "estimator/estimator_options.h"
#include "preintegration/imu_glitch_filter.h"
#include "preintegration/imu_types.h"

namespace vio {

struct ImuConfig {
  ImuNoise noise;
  PreintegrationOptions preintegration;
  ImuRange range;          // measuring range: beyond it a sample is a glitch
  double rate_hz = 200.0;  // nominal sample rate [Hz]
  double gravity_magnitude = 9.81;  // g in g_w = (0, 0, -g) [m/s^2]

  // The fields that belong to neither ImuNoise nor PreintegrationOptions, and
  // how they constrain those: rate_hz > 0, gravity_magnitude within Earth's
  // range [9.7, 9.9], max_sample_gap at least one nominal period 1 / rate_hz
  // (else every interval would be rejected). False with a message that starts
  // with the offending field's name otherwise.
  bool Validate(std::string* message) const;
};

// Reads and validates root's `imu` mapping; throws ConfigError.
ImuConfig LoadImuConfig(const YamlNode& root);

// Copies what the estimator takes from the imu: block into its options:
// gravity_magnitude and imu_stream (rate_hz and the measuring range). Tools
// call it after reading both blocks.
void ApplyImuConfig(const ImuConfig& imu, EstimatorOptions* options);

// Reads the four Kalibr noise keys (accelerometer_noise_density,
// gyroscope_noise_density, accelerometer_random_walk, gyroscope_random_walk)
// of `node`, as the `imu:` block, EuRoC's imu0/sensor.yaml and the simulator
// presets hold them. Throws ConfigError for a missing or non-numeric key; the
// caller validates (ValidateAt), so that its message names its own block.
ImuNoise ReadImuNoise(const YamlNode& node);

}  // namespace vio

#endif  // VIO_CONFIG_IMU_CONFIG_H_
