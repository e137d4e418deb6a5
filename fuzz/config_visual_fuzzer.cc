// The `visual:` block (config/visual_config.h: ReadVisualOptions).

#include "config/visual_config.h"
#include "fuzz/config_fuzzer.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  vio::fuzz::FuzzConfigBlock(data, size, [](const vio::YamlNode& root) {
    vio::fuzz::RequireValid(vio::ReadVisualOptions(root));
  });
  return 0;
}
