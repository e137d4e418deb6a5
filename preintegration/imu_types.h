#ifndef VIO_PREINTEGRATION_IMU_TYPES_H_
#define VIO_PREINTEGRATION_IMU_TYPES_H_

// Plain IMU data and noise parameters, shared by the dataset readers, the
// simulator, the preintegration and the estimator.

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace vio {

// One IMU sample in the body (IMU) frame B.
struct ImuSample {
  int64_t t_ns = 0;                               // stamp [ns]
  Eigen::Vector3d acc = Eigen::Vector3d::Zero();  // specific force [m/s^2]
  Eigen::Vector3d gyr = Eigen::Vector3d::Zero();  // angular rate [rad/s]
};

// Continuous-time IMU noise in the Kalibr / EuRoC sensor.yaml convention.
// For a step of length dt [s]: white noise sigma / sqrt(dt), bias random walk
// sigma * sqrt(dt). Defaults: EuRoC's ADIS16448 (imu0/sensor.yaml).
struct ImuNoise {
  double accelerometer_noise_density = 2.0e-3;  // [m/s^2/sqrt(Hz)]
  double gyroscope_noise_density = 1.6968e-4;   // [rad/s/sqrt(Hz)]
  double accelerometer_random_walk = 3.0e-3;    // [m/s^3/sqrt(Hz)]
  double gyroscope_random_walk = 1.9393e-5;     // [rad/s^2/sqrt(Hz)]

  // True when every density is finite and > 0; otherwise false with a message
  // that starts with the offending field's name.
  bool Validate(std::string* message) const {
    const struct {
      const char* name;
      double value;
    } fields[] = {{"accelerometer_noise_density", accelerometer_noise_density},
                  {"gyroscope_noise_density", gyroscope_noise_density},
                  {"accelerometer_random_walk", accelerometer_random_walk},
                  {"gyroscope_random_walk", gyroscope_random_walk}};
    for (const auto& f : fields) {
      if (!(std::isfinite(f.value) && f.value > 0.0)) {
        *message = std::string(f.name) + " must be > 0 (got " +
                   std::to_string(f.value) + ")";
        return false;
      }
    }
    return true;
  }
};

// Bad IMU input handed to the preintegration: a non-increasing stamp, a NaN or
// infinite sample, a gap longer than the limit, an interval the samples do not
// cover. what() names the offending stamp(s) in nanoseconds.
class ImuError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// Options of the preintegration (not the sensor's noise, see ImuNoise).
struct PreintegrationOptions {
  // Largest allowed time between two consecutive samples used in an interval
  // [s]; EuRoC's IMU runs at 200 Hz (5 ms), so the default tolerates three
  // dropped samples.
  double max_sample_gap = 0.02;
  // When the bias estimate leaves the linearisation bias by more than this
  // (Euclidean norm of the difference), the first-order correction is no
  // longer trusted and the interval is re-integrated from its samples.
  double repropagate_acc_bias_change = 0.1;   // [m/s^2]
  double repropagate_gyr_bias_change = 0.01;  // [rad/s]

  // True when every field is finite and > 0; otherwise false with a message
  // that starts with the offending field's name.
  bool Validate(std::string* message) const {
    const struct {
      const char* name;
      double value;
    } fields[] = {{"max_sample_gap", max_sample_gap},
                  {"repropagate_acc_bias_change", repropagate_acc_bias_change},
                  {"repropagate_gyr_bias_change", repropagate_gyr_bias_change}};
    for (const auto& f : fields) {
      if (!(std::isfinite(f.value) && f.value > 0.0)) {
        *message = std::string(f.name) + " must be > 0 (got " +
                   std::to_string(f.value) + ")";
        return false;
      }
    }
    return true;
  }
};

}  // namespace vio

#endif  // VIO_PREINTEGRATION_IMU_TYPES_H_
