#ifndef VIO_CONFIG_EUROC_SENSOR_H_
#define VIO_CONFIG_EUROC_SENSOR_H_

// The sensor.yaml files of the EuRoC ASL layout (Kalibr's format), mapped onto
// the structs their modules own: a camera's onto geometry's CameraCalibration,
// the IMU's onto preintegration's ImuNoise plus its rate.
//
// Camera keys (all required): camera_model (pinhole), intrinsics [fu, fv, cu,
// cv], distortion_model (radial-tangential | equidistant | none),
// distortion_coefficients [4], resolution [width, height], rate_hz, T_BS
// {rows: 4, cols: 4, data: [16, row-major]} with a rotation block that is
// orthonormal within 1e-6 and a last row 0 0 0 1.
// IMU keys (all required): rate_hz, accelerometer_noise_density,
// gyroscope_noise_density, accelerometer_random_walk, gyroscope_random_walk.
// Any fault is a ConfigError naming the file and the key.

#include <string>

#include "geometry/camera_model.h"
#include "preintegration/imu_types.h"

namespace vio {

// What imu0/sensor.yaml says about the IMU.
struct EurocImuSensor {
  ImuNoise noise;          // continuous-time densities (Kalibr units)
  double rate_hz = 200.0;  // [Hz]
};

CameraCalibration ReadEurocCameraYaml(const std::string& path);
EurocImuSensor ReadEurocImuYaml(const std::string& path);

}  // namespace vio

#endif  // VIO_CONFIG_EUROC_SENSOR_H_
