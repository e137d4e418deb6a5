#ifndef VIO_CONFIG_SIMULATOR_CONFIG_H_
#define VIO_CONFIG_SIMULATOR_CONFIG_H_

// Simulator presets (config/sim_*.yaml) <-> SimulatorOptions. Every key is
// required (a preset states the whole simulation); the camera calibrations are
// EuRoC's built-in ones and are not part of the file. Layout:
//
//   seed, start_time_ns, duration_s, gravity_m_s2
//   motion:  shape (ellipse | rotation | line | circle), still_duration_s,
//            blend_duration_s, radius_x_m, radius_y_m, lap_period_s, height_m,
//            height_amplitude_m, roll_amplitude_rad, pitch_amplitude_rad,
//            yaw_amplitude_rad, start_phase_s, attitude_rate_factor
//   imu:     rate_hz, add_noise, accelerometer_noise_density,
//            gyroscope_noise_density, accelerometer_random_walk,
//            gyroscope_random_walk, initial_accelerometer_bias [3],
//            initial_gyroscope_bias [3]
//   camera:  stereo, pixel_noise_px, max_features_per_frame,
//            min_feature_distance_px, track_drop_probability,
//            outlier_fraction, time_offset_s
//   room:    half_length_x_m, half_width_y_m, height_m, landmarks
//
// A missing key, a wrong type or an out-of-range value (Validate()) is a
// ConfigError naming the file and the key.

#include <string>

#include "dataset/simulator.h"

namespace vio {

SimulatorOptions LoadSimulatorOptions(const std::string& path);

// The options as YAML in the layout above (numbers printed exactly), so that
// loading the text gives the same options back. Tools print it as the
// effective configuration.
std::string SimulatorOptionsToYaml(const SimulatorOptions& options);

}  // namespace vio

#endif  // VIO_CONFIG_SIMULATOR_CONFIG_H_
