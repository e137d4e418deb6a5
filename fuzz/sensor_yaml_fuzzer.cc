// A sensor.yaml of the EuRoC layout (config/euroc_sensor.h), read both as a
// camera's and as the IMU's, as LoadEurocSequence reads camN/ and imu0/. A
// camera that reads must give a working camera model: Validate() accepts it,
// and a pixel at the image centre goes to the normalised plane and back.

#include <cstddef>
#include <cstdint>

#include "config/euroc_sensor.h"
#include "config/yaml_reader.h"
#include "fuzz/fuzz_input.h"
#include "geometry/camera_model.h"

namespace {

void CheckCamera(const vio::CameraCalibration& calibration) {
  std::string message;
  vio::fuzz::Require(calibration.Validate(&message),
                     "a calibration Validate() refuses: " + message);
  const vio::CameraModel camera(calibration);
  const Eigen::Vector2d centre(calibration.cx, calibration.cy);
  Eigen::Vector2d xy;
  if (camera.PixelToNormalized(centre, &xy)) {
    Eigen::Vector2d uv;
    camera.Project(Eigen::Vector3d(xy.x(), xy.y(), 1.0), &uv);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static vio::fuzz::ScratchFile file("sensor.yaml");
  const std::string& path = file.Write(data, size);
  try {
    CheckCamera(vio::ReadEurocCameraYaml(path));
  } catch (const vio::ConfigError& e) {
    vio::fuzz::RequireNamesFile(e.what(), path);
  }
  try {
    const vio::EurocImuSensor imu = vio::ReadEurocImuYaml(path);
    std::string message;
    vio::fuzz::Require(
        imu.noise.Validate(&message) && imu.rate_hz > 0.0,
        "an IMU sensor.yaml read into invalid values: " + message);
  } catch (const vio::ConfigError& e) {
    vio::fuzz::RequireNamesFile(e.what(), path);
  }
  return 0;
}
