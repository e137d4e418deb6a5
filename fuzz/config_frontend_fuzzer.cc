// The `frontend:` block (config/frontend_config.h: ReadFrontendOptions).

#include "config/frontend_config.h"
#include "fuzz/config_fuzzer.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  vio::fuzz::FuzzConfigBlock(data, size, [](const vio::YamlNode& root) {
    vio::fuzz::RequireValid(vio::ReadFrontendOptions(root.Child("frontend")));
  });
  return 0;
}
