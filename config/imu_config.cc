#include "config/imu_config.h"

#include <cmath>
#include <sstream>

namespace vio {
namespace {

std::string Shown(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

}  // namespace

bool ImuConfig::Validate(std::string* message) const {
  if (!(std::isfinite(rate_hz) && rate_hz > 0.0)) {
    *message = "rate_hz must be > 0 (got " + Shown(rate_hz) + ")";
    return false;
  }
  if (!(gravity_magnitude >= 9.7 && gravity_magnitude <= 9.9)) {
    *message = "gravity_magnitude must be in [9.7, 9.9] m/s^2 (got " +
               Shown(gravity_magnitude) + ")";
    return false;
  }
  if (preintegration.max_sample_gap < 1.0 / rate_hz) {
    *message =
        "max_sample_gap must be at least one sample period 1 / rate_hz = " +
        Shown(1.0 / rate_hz) + " s (got " +
        Shown(preintegration.max_sample_gap) + ")";
    return false;
  }
  return true;
}

ImuNoise ReadImuNoise(const YamlNode& node) {
  ImuNoise noise;
  noise.accelerometer_noise_density =
      node.Get<double>("accelerometer_noise_density");
  noise.gyroscope_noise_density = node.Get<double>("gyroscope_noise_density");
  noise.accelerometer_random_walk =
      node.Get<double>("accelerometer_random_walk");
  noise.gyroscope_random_walk = node.Get<double>("gyroscope_random_walk");
  return noise;
}

bool ParseImuNoiseSource(const std::string& name, ImuNoiseSource* source) {
  if (name == "config") {
    *source = ImuNoiseSource::kConfig;
  } else if (name == "sequence") {
    *source = ImuNoiseSource::kSequence;
  } else {
    return false;
  }
  return true;
}

const char* ImuNoiseSourceName(ImuNoiseSource source) {
  return source == ImuNoiseSource::kConfig ? "config" : "sequence";
}

void ApplyImuConfig(const ImuConfig& imu, EstimatorOptions* options) {
  options->gravity_magnitude = imu.gravity_magnitude;
  options->imu_stream.rate_hz = imu.rate_hz;
  options->imu_stream.range = imu.range;
  options->imu_stream.noise_adaptation.enabled = imu.adapt_noise;
}

ImuConfig LoadImuConfig(const YamlNode& root) {
  const YamlNode imu = root.Child("imu");
  ImuConfig c;
  const std::string source = imu.Get<std::string>("noise_from");
  if (!ParseImuNoiseSource(source, &c.noise_from)) {
    throw ConfigError(imu.Where("noise_from") +
                      " must be config or sequence (got '" + source + "')");
  }
  c.rate_hz = imu.Get<double>("rate_hz");
  c.noise = ReadImuNoise(imu);
  c.adapt_noise = imu.Get<bool>("adapt_noise");
  c.gravity_magnitude = imu.Get<double>("gravity_magnitude");
  c.preintegration.max_sample_gap = imu.Get<double>("max_sample_gap");
  c.preintegration.repropagate_acc_bias_change =
      imu.Get<double>("repropagate_acc_bias_change");
  c.preintegration.repropagate_gyr_bias_change =
      imu.Get<double>("repropagate_gyr_bias_change");
  c.range.accelerometer_range = imu.Get<double>("accelerometer_range");
  c.range.gyroscope_range = imu.Get<double>("gyroscope_range");
  // The module's own checks first, so each message names its field.
  ValidateAt(imu, c.noise);
  ValidateAt(imu, c.preintegration);
  ValidateAt(imu, c.range);
  ValidateAt(imu, c);
  return c;
}

}  // namespace vio
