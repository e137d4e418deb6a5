#include "config/yaml_reader.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "test/testing/expect_error.h"

namespace vio {
namespace {

const char kDoc[] = R"(
imu:
  rate_hz: 200
  gyro_noise_density: 1.6968e-04
  name: adis
  flags: [1, 2, 3]
  enabled: true
)";

TEST(YamlReader, ReadsTypedValues) {
  const YamlNode root = YamlNode::LoadString(kDoc, "mem.yaml");
  const YamlNode imu = root.Child("imu");
  EXPECT_EQ(imu.Get<int>("rate_hz"), 200);
  EXPECT_DOUBLE_EQ(imu.Get<double>("gyro_noise_density"), 1.6968e-4);
  EXPECT_EQ(imu.Get<std::string>("name"), "adis");
  EXPECT_TRUE(imu.Get<bool>("enabled"));
  EXPECT_EQ(imu.GetVector("flags", 3), (std::vector<double>{1, 2, 3}));
}

TEST(YamlReader, MissingKeyNamesFileAndPath) {
  const YamlNode imu = YamlNode::LoadString(kDoc, "mem.yaml").Child("imu");
  ExpectErrorContaining<ConfigError>(
      [&] { imu.Get<double>("acc_noise_density"); },
      "mem.yaml: imu.acc_noise_density is missing");
}

TEST(YamlReader, WrongTypeNamesValue) {
  const YamlNode imu = YamlNode::LoadString(kDoc, "mem.yaml").Child("imu");
  ExpectErrorContaining<ConfigError>(
      [&] { imu.Get<double>("name"); },
      "mem.yaml: imu.name must be a number (got 'adis')");
  ExpectErrorContaining<ConfigError>(
      [&] { imu.Get<int>("gyro_noise_density"); },
      "imu.gyro_noise_density must be an integer");
  ExpectErrorContaining<ConfigError>([&] { imu.GetVector("flags", 2); },
                                     "imu.flags must have 2 numbers (got 3)");
  ExpectErrorContaining<ConfigError>([&] { imu.Child("rate_hz"); },
                                     "imu.rate_hz must be a mapping");
}

TEST(YamlReader, UnreadableAndMalformedFiles) {
  ExpectErrorContaining<ConfigError>(
      [] { YamlNode::LoadFile("/nonexistent/x.yaml"); },
      "/nonexistent/x.yaml: cannot open the file");
  ExpectErrorContaining<ConfigError>(
      [] { YamlNode::LoadString("a: [1, 2", "bad.yaml"); }, "bad.yaml:");
  ExpectErrorContaining<ConfigError>(
      [] { YamlNode::LoadString("- 1\n- 2\n", "list.yaml"); },
      "list.yaml: the top level must be a mapping");
}

struct FakeOptions {
  double rate_hz = 0.0;
  bool Validate(std::string* message) const {
    if (rate_hz > 0.0) return true;
    *message = "rate_hz must be > 0 (got " + std::to_string(rate_hz) + ")";
    return false;
  }
};

TEST(YamlReader, ValidateAtPrefixesFileAndBlock) {
  const YamlNode imu = YamlNode::LoadString(kDoc, "mem.yaml").Child("imu");
  FakeOptions options;
  ExpectErrorContaining<ConfigError>([&] { ValidateAt(imu, options); },
                                     "mem.yaml: imu.rate_hz must be > 0");
}

}  // namespace
}  // namespace vio
