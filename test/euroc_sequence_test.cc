#include "config/euroc_sequence.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "config/yaml_reader.h"
#include "dataset/csv.h"
#include "test/testing/expect_error.h"
#include "test/testing/temp_folder.h"

namespace vio {
namespace {

using testing::TempFolder;

const std::string kV101 =
    std::string(VIO_SHARED_DIR) + "/data/euroc_V1_01_first5s";
const std::string kMh05 =
    std::string(VIO_SHARED_DIR) + "/data/euroc_MH_05_imu_gt";

std::string ReadText(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// `text` without the lines from the one starting with `key` up to (not
// including) the next line that starts without indentation.
std::string WithoutKey(const std::string& text, const std::string& key) {
  std::istringstream in(text);
  std::ostringstream out;
  std::string line;
  bool skipping = false;
  while (std::getline(in, line)) {
    if (line.rfind(key + ":", 0) == 0) {
      skipping = true;
      continue;
    }
    if (skipping && !line.empty() && line[0] == ' ') continue;
    skipping = false;
    out << line << '\n';
  }
  return out.str();
}

std::string Replaced(std::string text, const std::string& from,
                     const std::string& to) {
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

// EuRoC's files begin with OpenCV's "%YAML:1.0"; yaml-cpp 0.7 reads it as an
// unknown directive ("YAML:1.0" is not "YAML") and ignores it, so no
// stripping is needed. This test keeps that assumption checked.
TEST(EurocSensor, OpenCvYamlDirectiveIsAccepted) {
  const YamlNode node =
      YamlNode::LoadString("%YAML:1.0\n# comment\nrate_hz: 200\n", "s.yaml");
  EXPECT_EQ(node.Get<int>("rate_hz"), 200);
}

TEST(EurocSequence, RealV101CalibrationsEqualTheSensorYamlValues) {
  const EurocSequence sequence = LoadEurocSequence(kV101);
  ASSERT_EQ(sequence.cameras.size(), 2u);
  const CameraCalibration& cam0 = sequence.cameras[0];
  EXPECT_EQ(cam0.width, 752);
  EXPECT_EQ(cam0.height, 480);
  EXPECT_EQ(cam0.rate_hz, 20.0);
  EXPECT_EQ(cam0.fx, 458.654);
  EXPECT_EQ(cam0.fy, 457.296);
  EXPECT_EQ(cam0.cx, 367.215);
  EXPECT_EQ(cam0.cy, 248.375);
  EXPECT_EQ(cam0.distortion, DistortionModel::kRadialTangential);
  EXPECT_EQ(
      cam0.distortion_coefficients,
      Eigen::Vector4d(-0.28340811, 0.07395907, 0.00019359, 1.76187114e-05));
  Eigen::Matrix3d R_b_c0;
  R_b_c0 << 0.0148655429818, -0.999880929698, 0.00414029679422,  //
      0.999557249008, 0.0149672133247, 0.025715529948,           //
      -0.0257744366974, 0.00375618835797, 0.999660727178;
  EXPECT_LT((cam0.q_b_c.toRotationMatrix() - R_b_c0).norm(), 1e-9);
  EXPECT_EQ(cam0.t_b_c, Eigen::Vector3d(-0.0216401454975, -0.064676986768,
                                        0.00981073058949));
  const CameraCalibration& cam1 = sequence.cameras[1];
  EXPECT_EQ(cam1.fx, 457.587);
  EXPECT_EQ(cam1.distortion_coefficients[3], -3.55590700e-05);
  EXPECT_EQ(cam1.t_b_c.y(), 0.0453689425024);
  // Stereo baseline of the VI-Sensor: about 11 cm.
  EXPECT_NEAR((cam1.t_b_c - cam0.t_b_c).norm(), 0.110, 0.001);
  EXPECT_EQ(sequence.imu.rate_hz, 200.0);
  EXPECT_EQ(sequence.imu.noise.gyroscope_noise_density, 1.6968e-04);
  EXPECT_EQ(sequence.imu.noise.gyroscope_random_walk, 1.9393e-05);
  EXPECT_EQ(sequence.imu.noise.accelerometer_noise_density, 2.0e-3);
  EXPECT_EQ(sequence.imu.noise.accelerometer_random_walk, 3.0e-3);
  EXPECT_EQ(sequence.data.cameras[1].missing_images, 4);
}

TEST(EurocSequence, RealMh05LoadsWithoutAnyCamera) {
  const EurocSequence sequence = LoadEurocSequence(kMh05);
  EXPECT_TRUE(sequence.cameras.empty());
  EXPECT_EQ(sequence.imu.noise.accelerometer_noise_density, 2.0e-3);
  EXPECT_FALSE(sequence.data.ground_truth.empty());
}

// A copy of the real V1_01 camera sensor.yaml, altered, must fail naming
// the key.
TEST(EurocSensor, EveryMissingCameraKeyIsNamed) {
  TempFolder dir;
  const std::string yaml = ReadText(kV101 + "/mav0/cam0/sensor.yaml");
  for (const char* key :
       {"camera_model", "intrinsics", "distortion_model",
        "distortion_coefficients", "resolution", "rate_hz", "T_BS"}) {
    SCOPED_TRACE(key);
    dir.Write("cam.yaml", WithoutKey(yaml, key));
    ExpectErrorContaining<ConfigError>(
        [&] { ReadEurocCameraYaml(dir.Path("cam.yaml")); },
        dir.Path("cam.yaml") + ": " + key + " is missing");
  }
}

TEST(EurocSensor, BadCameraValuesAreNamed) {
  TempFolder dir;
  const std::string yaml = ReadText(kV101 + "/mav0/cam0/sensor.yaml");
  const struct {
    std::string from, to, message;
  } cases[] = {
      {"camera_model: pinhole", "camera_model: omni",
       "camera_model must be pinhole (got 'omni')"},
      {"distortion_model: radial-tangential", "distortion_model: fancy",
       "distortion_model must be radial-tangential, equidistant or none (got "
       "'fancy')"},
      {"intrinsics: [458.654, ", "intrinsics: [",
       "intrinsics must have 4 numbers (got 3)"},
      {"intrinsics: [458.654", "intrinsics: [-458.654",
       "intrinsics: focal lengths must be > 0"},
      {"resolution: [752, 480]", "resolution: [752, x]",
       "resolution[1] must be a number"},
      {"resolution: [752, 480]", "resolution: [60727200000, 480]",
       "resolution must hold whole numbers from 1 to 100000 (got "
       "60727200000.000000)"},
      {"resolution: [752, 480]", "resolution: [752, 0]",
       "resolution must hold whole numbers from 1 to 100000 (got 0.000000)"},
      {"resolution: [752, 480]", "resolution: [752.5, 480]",
       "resolution must hold whole numbers from 1 to 100000 (got "
       "752.500000)"},
      {"rate_hz: 20", "rate_hz: fast", "rate_hz must be a number (got 'fast')"},
      {"rows: 4", "rows: 3", "T_BS.rows and cols must both be 4"},
      {"data: [0.0148655429818", "data: [0.5",
       "T_BS.data: the rotation block is not a rotation"},
      {"0.0, 0.0, 0.0, 1.0]", "0.0, 0.0, 1.0, 1.0]",
       "T_BS.data: the last row must be 0 0 0 1"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.message);
    dir.Write("cam.yaml", Replaced(yaml, c.from, c.to));
    ExpectErrorContaining<ConfigError>(
        [&] { ReadEurocCameraYaml(dir.Path("cam.yaml")); },
        dir.Path("cam.yaml") + ": " + c.message);
  }
}

TEST(EurocSensor, EveryMissingOrBadImuKeyIsNamed) {
  TempFolder dir;
  const std::string yaml = ReadText(kV101 + "/mav0/imu0/sensor.yaml");
  for (const char* key :
       {"rate_hz", "accelerometer_noise_density", "gyroscope_noise_density",
        "accelerometer_random_walk", "gyroscope_random_walk"}) {
    SCOPED_TRACE(key);
    dir.Write("imu.yaml", WithoutKey(yaml, key));
    ExpectErrorContaining<ConfigError>(
        [&] { ReadEurocImuYaml(dir.Path("imu.yaml")); },
        dir.Path("imu.yaml") + ": " + key + " is missing");
  }
  dir.Write("imu.yaml", Replaced(yaml, "gyroscope_random_walk: 1.9393e-05",
                                 "gyroscope_random_walk: -1"));
  ExpectErrorContaining<ConfigError>(
      [&] { ReadEurocImuYaml(dir.Path("imu.yaml")); },
      "imu.yaml: gyroscope_random_walk must be > 0");
}

TEST(EurocSequence, MissingSensorYamlIsAConfigErrorNamingIt) {
  TempFolder dir;
  dir.Write("mav0/imu0/data.csv", "1000000000,0,0,0,9.8,0,0\n");
  dir.Write("mav0/cam0/features.csv", "1000000000,1,10,20\n");
  ExpectErrorContaining<ConfigError>(
      [&] { LoadEurocSequence(dir.path()); },
      dir.Path("mav0/imu0/sensor.yaml") + ": cannot open");
  dir.Write("mav0/imu0/sensor.yaml",
            ReadText(kV101 + "/mav0/imu0/sensor.yaml"));
  ExpectErrorContaining<ConfigError>(
      [&] { LoadEurocSequence(dir.path()); },
      dir.Path("mav0/cam0/sensor.yaml") + ": cannot open");
  dir.Write("mav0/cam0/sensor.yaml",
            ReadText(kV101 + "/mav0/cam0/sensor.yaml"));
  EXPECT_EQ(LoadEurocSequence(dir.path()).cameras.size(), 1u);
}

}  // namespace
}  // namespace vio
