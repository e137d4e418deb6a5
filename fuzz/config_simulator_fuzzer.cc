// A simulator preset, config/sim_*.yaml (config/simulator_config.h:
// LoadSimulatorOptions). What loads must also survive the round trip the
// tools rely on: written back as YAML (SimulatorOptionsToYaml) and loaded
// again, it gives the same text.

#include <cstddef>
#include <cstdint>

#include "config/simulator_config.h"
#include "config/yaml_reader.h"
#include "fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static vio::fuzz::ScratchFile file("sim_preset.yaml");
  static vio::fuzz::ScratchFile again("sim_preset_again.yaml");
  const std::string& path = file.Write(data, size);
  vio::SimulatorOptions options;
  try {
    options = vio::LoadSimulatorOptions(path);
  } catch (const vio::ConfigError& e) {
    vio::fuzz::RequireNamesFile(e.what(), path);
    return 0;
  }
  std::string message;
  vio::fuzz::Require(options.Validate(&message),
                     "loaded options Validate() refuses: " + message);
  const std::string yaml = vio::SimulatorOptionsToYaml(options);
  again.Write(reinterpret_cast<const uint8_t*>(yaml.data()), yaml.size());
  try {
    vio::fuzz::Require(vio::SimulatorOptionsToYaml(
                           vio::LoadSimulatorOptions(again.path())) == yaml,
                       "the written preset reads back differently:\n" + yaml);
  } catch (const vio::ConfigError& e) {
    vio::fuzz::Require(false, "the written preset does not load: " +
                                  std::string(e.what()) + "\n" + yaml);
  }
  return 0;
}
