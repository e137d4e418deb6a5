#include "config/euroc_sensor.h"

#include <Eigen/Core>
#include <cmath>
#include <string>
#include <vector>

#include "config/imu_config.h"
#include "config/yaml_reader.h"

namespace vio {
namespace {

constexpr double kRotationTolerance = 1e-6;

// T_BS: the camera's pose in the body frame, 4x4 row-major.
void ReadTbs(const YamlNode& root, CameraCalibration* calibration) {
  const YamlNode tbs = root.Child("T_BS");
  if (tbs.Get<int>("rows") != 4 || tbs.Get<int>("cols") != 4) {
    tbs.Fail("rows and cols must both be 4");
  }
  const std::vector<double> data = tbs.GetVector("data", 16);
  const Eigen::Matrix4d T_b_c =
      Eigen::Map<const Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(
          data.data());
  if (!T_b_c.allFinite()) tbs.Fail("data must be finite");
  if ((T_b_c.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).norm() > 1e-12) {
    tbs.Fail("data: the last row must be 0 0 0 1");
  }
  const Eigen::Matrix3d R_b_c = T_b_c.topLeftCorner<3, 3>();
  const double error =
      (R_b_c.transpose() * R_b_c - Eigen::Matrix3d::Identity()).norm();
  if (error > kRotationTolerance || R_b_c.determinant() < 0.0) {
    tbs.Fail("data: the rotation block is not a rotation (|R^T R - I| = " +
             std::to_string(error) + ", det " +
             std::to_string(R_b_c.determinant()) + ")");
  }
  calibration->q_b_c = Eigen::Quaterniond(R_b_c).normalized();
  calibration->t_b_c = T_b_c.topRightCorner<3, 1>();
}

}  // namespace

CameraCalibration ReadEurocCameraYaml(const std::string& path) {
  const YamlNode root = YamlNode::LoadFile(path);
  CameraCalibration calibration;
  const std::string model = root.Get<std::string>("camera_model");
  if (model != "pinhole") {
    throw ConfigError(root.Where("camera_model") + " must be pinhole (got '" +
                      model + "')");
  }
  const std::vector<double> k = root.GetVector("intrinsics", 4);
  calibration.fx = k[0];
  calibration.fy = k[1];
  calibration.cx = k[2];
  calibration.cy = k[3];
  const std::string distortion = root.Get<std::string>("distortion_model");
  if (!ParseDistortionModel(distortion, &calibration.distortion)) {
    throw ConfigError(root.Where("distortion_model") +
                      " must be radial-tangential, equidistant or none (got '" +
                      distortion + "')");
  }
  const std::vector<double> d = root.GetVector("distortion_coefficients", 4);
  calibration.distortion_coefficients = {d[0], d[1], d[2], d[3]};
  const std::vector<double> resolution = root.GetVector("resolution", 2);
  // Whole pixels within an int before the cast (a larger double is undefined
  // behaviour when converted; the fuzzer found 6.07e10).
  constexpr double kMaxResolutionPx = 100000.0;
  for (double r : resolution) {
    if (!(r >= 1.0 && r <= kMaxResolutionPx && r == std::floor(r))) {
      throw ConfigError(root.Where("resolution") +
                        " must hold whole numbers from 1 to 100000 (got " +
                        std::to_string(r) + ")");
    }
  }
  calibration.width = static_cast<int>(resolution[0]);
  calibration.height = static_cast<int>(resolution[1]);
  calibration.rate_hz = root.Get<double>("rate_hz");
  ReadTbs(root, &calibration);
  ValidateAt(root, calibration);
  return calibration;
}

EurocImuSensor ReadEurocImuYaml(const std::string& path) {
  const YamlNode root = YamlNode::LoadFile(path);
  EurocImuSensor imu;
  imu.rate_hz = root.Get<double>("rate_hz");
  if (!(std::isfinite(imu.rate_hz) && imu.rate_hz > 0.0)) {
    root.Fail("rate_hz must be > 0 (got " + std::to_string(imu.rate_hz) + ")");
  }
  imu.noise = ReadImuNoise(root);
  ValidateAt(root, imu.noise);
  return imu;
}

}  // namespace vio
