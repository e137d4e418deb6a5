// The `imu:` block (config/imu_config.h: LoadImuConfig).

#include "config/imu_config.h"
#include "fuzz/config_fuzzer.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  vio::fuzz::FuzzConfigBlock(data, size, [](const vio::YamlNode& root) {
    const vio::ImuConfig config = vio::LoadImuConfig(root);
    vio::fuzz::RequireValid(config);
    vio::fuzz::RequireValid(config.noise);
    vio::fuzz::RequireValid(config.preintegration);
  });
  return 0;
}
