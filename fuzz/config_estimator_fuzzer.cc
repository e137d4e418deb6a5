// The `estimator:` block (config/estimator_config.h: ReadEstimatorOptions),
// and the listing tools print of what was read.

#include "config/estimator_config.h"
#include "fuzz/config_fuzzer.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  vio::fuzz::FuzzConfigBlock(data, size, [](const vio::YamlNode& root) {
    const vio::EstimatorOptions options = vio::ReadEstimatorOptions(root);
    vio::fuzz::RequireValid(options);
    vio::fuzz::Require(!vio::DescribeEstimatorOptions(options).empty(),
                       "an empty description");
  });
  return 0;
}
