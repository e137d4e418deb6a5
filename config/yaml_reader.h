#ifndef VIO_CONFIG_YAML_READER_H_
#define VIO_CONFIG_YAML_READER_H_

// The only yaml-cpp code of the project lives in config/. YamlNode wraps a
// node together with the file it came from and its key path, so that every
// error names both: "config/euroc.yaml: imu.gyro_noise_density must be > 0
// (got -0.1)". A missing required key is an error, never a silent default.

#include <yaml-cpp/yaml.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace vio {

// Any problem with a configuration file: unreadable, malformed, a missing
// key, a wrong type or an out-of-range value. what() names file and key.
class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class YamlNode {
 public:
  // Parses a file; throws ConfigError naming it when it cannot be read or
  // parsed, or when its top level is not a mapping.
  static YamlNode LoadFile(const std::string& path);
  // Parses text held in memory; `name` stands for the file in messages.
  static YamlNode LoadString(const std::string& text, const std::string& name);

  bool Has(const std::string& key) const;

  // The mapping under `key`; throws when it is missing or not a mapping.
  YamlNode Child(const std::string& key) const;

  // A required scalar of type T (double, int, bool, std::string, int64_t).
  // Throws when it is missing or does not convert to T.
  template <typename T>
  T Get(const std::string& key) const;

  // A required sequence of exactly `size` numbers (size < 0: any length).
  std::vector<double> GetVector(const std::string& key, int size) const;
  // A required sequence (possibly empty) of rows of exactly `columns`
  // numbers each, e.g. "boxes: [[0, 0, 1, 1, 1], [2, 1, 1, 1, 2]]".
  std::vector<std::vector<double>> GetRows(const std::string& key,
                                           int columns) const;

  // "file: path.key", for messages.
  std::string Where(const std::string& key) const;
  const std::string& file() const { return file_; }

  // Throws ConfigError "<file>: <path>.<message>" — for Validate() messages of
  // options structs, which start with the offending field's name.
  [[noreturn]] void Fail(const std::string& message) const;

 private:
  YamlNode(YAML::Node node, std::string file, std::string path)
      : node_(std::move(node)),
        file_(std::move(file)),
        path_(std::move(path)) {}

  YAML::Node Required(const std::string& key) const;

  YAML::Node node_;
  std::string file_;
  std::string path_;  // "" at the top level, else "a.b"
};

// Calls options.Validate(&message) and turns a failure into a ConfigError
// located at `node` (the mapping the options were read from).
template <typename Options>
void ValidateAt(const YamlNode& node, const Options& options) {
  std::string message;
  if (!options.Validate(&message)) node.Fail(message);
}

}  // namespace vio

#endif  // VIO_CONFIG_YAML_READER_H_
