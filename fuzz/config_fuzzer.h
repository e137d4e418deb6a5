#ifndef VIO_FUZZ_CONFIG_FUZZER_H_
#define VIO_FUZZ_CONFIG_FUZZER_H_

// The body of every configuration-block harness: the input is a whole YAML
// file (config/yaml_reader.h parses it, as the tools do), `read` maps one
// block onto its options struct and checks what it got. A refusal must be a
// ConfigError naming the file; any other exception escapes and is a finding.

#include <cstddef>
#include <cstdint>
#include <string>

#include "config/yaml_reader.h"
#include "fuzz/fuzz_input.h"

namespace vio::fuzz {

constexpr char kConfigName[] = "fuzz_config.yaml";

template <typename ReadBlock>
void FuzzConfigBlock(const uint8_t* data, size_t size, ReadBlock read) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    read(YamlNode::LoadString(text, kConfigName));
  } catch (const ConfigError& e) {
    RequireNamesFile(e.what(), kConfigName);
  }
}

// Aborts unless options.Validate() accepts what a reader returned.
template <typename Options>
void RequireValid(const Options& options) {
  std::string message;
  Require(options.Validate(&message),
          "the reader returned options Validate() refuses: " + message);
}

}  // namespace vio::fuzz

#endif  // VIO_FUZZ_CONFIG_FUZZER_H_
