#ifndef VIO_CONFIG_IMU_CONFIG_H_
#define VIO_CONFIG_IMU_CONFIG_H_

// The `imu:` block of a configuration file (config/default.yaml):
//
//   imu:
//     noise_from: config                    # config | sequence (below)
//     rate_hz: 200                          # nominal sample rate [Hz]
//     accelerometer_noise_density: 2.0e-3   # [m/s^2/sqrt(Hz)]   (Kalibr names
//     gyroscope_noise_density: 1.6968e-4    # [rad/s/sqrt(Hz)]    and units,
//     accelerometer_random_walk: 3.0e-3     # [m/s^3/sqrt(Hz)]    as in EuRoC's
//     gyroscope_random_walk: 1.9393e-5      # [rad/s^2/sqrt(Hz)]  sensor.yaml)
//     adapt_noise: false                    # online white-noise scale
//     gravity_magnitude: 9.81               # [m/s^2]
//     max_sample_gap: 0.02                  # [s]
//     repropagate_acc_bias_change: 0.1      # [m/s^2]
//     repropagate_gyr_bias_change: 0.01     # [rad/s]
//     accelerometer_range: 176.52           # per axis [m/s^2]
//     gyroscope_range: 17.453               # per axis [rad/s]
//
// noise_from says which noise densities the estimator assumes: `config`, the
// four keys of this block (they win: a user tunes them for the vehicle, as
// VINS-Mono, OKVIS and Basalt users do); `sequence`, those of the replayed
// folder's mav0/imu0/sensor.yaml (the four keys are then read and validated
// but not used). Tools may override it (vio_replay --imu-noise).
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

// Where the estimator's IMU noise densities come from.
enum class ImuNoiseSource {
  kConfig,    // the imu: block's four keys
  kSequence,  // the replayed sequence's imu0/sensor.yaml
};

struct ImuConfig {
  ImuNoiseSource noise_from = ImuNoiseSource::kConfig;
  // As config/default.yaml: the ADIS16448's random walks, its white noise 15
  // (accelerometer) and 2 (gyroscope) times the datasheet's (EuRoC's flying
  // MAV with the landmarks kept as world points; issue 11,
  // docs/recorded_flights.md).
  ImuNoise noise{3.0e-2, 3.3936e-4, 3.0e-3, 1.9393e-5};
  PreintegrationOptions preintegration;
  // Scale the white-noise densities online from the window's IMU residuals
  // (estimator/imu_noise_adaptation.h); ApplyImuConfig passes it on.
  bool adapt_noise = false;
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
// gravity_magnitude and imu_stream (rate_hz, the measuring range and
// adapt_noise). Tools
// call it after reading both blocks.
void ApplyImuConfig(const ImuConfig& imu, EstimatorOptions* options);

// Reads the four Kalibr noise keys (accelerometer_noise_density,
// gyroscope_noise_density, accelerometer_random_walk, gyroscope_random_walk)
// of `node`, as the `imu:` block, EuRoC's imu0/sensor.yaml and the simulator
// presets hold them. Throws ConfigError for a missing or non-numeric key; the
// caller validates (ValidateAt), so that its message names its own block.
ImuNoise ReadImuNoise(const YamlNode& node);

// "config" / "sequence" <-> ImuNoiseSource; false for any other name.
bool ParseImuNoiseSource(const std::string& name, ImuNoiseSource* source);
const char* ImuNoiseSourceName(ImuNoiseSource source);

}  // namespace vio

#endif  // VIO_CONFIG_IMU_CONFIG_H_
