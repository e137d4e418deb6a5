#include "config/yaml_reader.h"

#include <cstdint>
#include <sstream>

namespace vio {
namespace {

template <typename T>
const char* TypeName();
template <>
const char* TypeName<double>() {
  return "a number";
}
template <>
const char* TypeName<int>() {
  return "an integer";
}
template <>
const char* TypeName<int64_t>() {
  return "an integer";
}
template <>
const char* TypeName<bool>() {
  return "true or false";
}
template <>
const char* TypeName<std::string>() {
  return "a string";
}

std::string Shown(const YAML::Node& n) {
  std::ostringstream out;
  out << n;
  return out.str();
}

}  // namespace

YamlNode YamlNode::LoadFile(const std::string& path) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    throw ConfigError(path + ": cannot open the file");
  } catch (const YAML::Exception& e) {
    throw ConfigError(path + ":" + std::to_string(e.mark.line + 1) + ": " +
                      e.msg);
  }
  if (!root.IsMap())
    throw ConfigError(path + ": the top level must be a mapping");
  return YamlNode(root, path, "");
}

YamlNode YamlNode::LoadString(const std::string& text,
                              const std::string& name) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw ConfigError(name + ":" + std::to_string(e.mark.line + 1) + ": " +
                      e.msg);
  }
  if (!root.IsMap())
    throw ConfigError(name + ": the top level must be a mapping");
  return YamlNode(root, name, "");
}

std::string YamlNode::Where(const std::string& key) const {
  return file_ + ": " + (path_.empty() ? key : path_ + "." + key);
}

void YamlNode::Fail(const std::string& message) const {
  throw ConfigError(file_ + ": " + (path_.empty() ? "" : path_ + ".") +
                    message);
}

bool YamlNode::Has(const std::string& key) const {
  return node_[key].IsDefined() && !node_[key].IsNull();
}

YAML::Node YamlNode::Required(const std::string& key) const {
  const YAML::Node n = node_[key];
  if (!n.IsDefined() || n.IsNull()) {
    throw ConfigError(Where(key) + " is missing");
  }
  return n;
}

YamlNode YamlNode::Child(const std::string& key) const {
  const YAML::Node n = Required(key);
  if (!n.IsMap()) throw ConfigError(Where(key) + " must be a mapping");
  return YamlNode(n, file_, path_.empty() ? key : path_ + "." + key);
}

template <typename T>
T YamlNode::Get(const std::string& key) const {
  const YAML::Node n = Required(key);
  if (!n.IsScalar()) {
    throw ConfigError(Where(key) + " must be " + TypeName<T>() + " (got " +
                      Shown(n) + ")");
  }
  try {
    return n.as<T>();
  } catch (const YAML::Exception&) {
    throw ConfigError(Where(key) + " must be " + TypeName<T>() + " (got '" +
                      n.Scalar() + "')");
  }
}

template double YamlNode::Get<double>(const std::string&) const;
template int YamlNode::Get<int>(const std::string&) const;
template int64_t YamlNode::Get<int64_t>(const std::string&) const;
template bool YamlNode::Get<bool>(const std::string&) const;
template std::string YamlNode::Get<std::string>(const std::string&) const;

std::vector<double> YamlNode::GetVector(const std::string& key,
                                        int size) const {
  const YAML::Node n = Required(key);
  if (!n.IsSequence()) {
    throw ConfigError(Where(key) + " must be a list of numbers");
  }
  if (size >= 0 && static_cast<int>(n.size()) != size) {
    throw ConfigError(Where(key) + " must have " + std::to_string(size) +
                      " numbers (got " + std::to_string(n.size()) + ")");
  }
  std::vector<double> out;
  for (size_t i = 0; i < n.size(); ++i) {
    try {
      out.push_back(n[i].as<double>());
    } catch (const YAML::Exception&) {
      throw ConfigError(Where(key) + "[" + std::to_string(i) +
                        "] must be a number (got " + Shown(n[i]) + ")");
    }
  }
  return out;
}

std::vector<std::vector<double>> YamlNode::GetRows(const std::string& key,
                                                   int columns) const {
  const YAML::Node n = Required(key);
  const std::string shape =
      " must be a list of rows of " + std::to_string(columns) + " numbers";
  if (!n.IsSequence()) throw ConfigError(Where(key) + shape);
  std::vector<std::vector<double>> rows;
  for (size_t i = 0; i < n.size(); ++i) {
    const std::string where = Where(key) + "[" + std::to_string(i) + "]";
    if (!n[i].IsSequence() || static_cast<int>(n[i].size()) != columns) {
      throw ConfigError(where + " must be a row of " + std::to_string(columns) +
                        " numbers");
    }
    std::vector<double> row;
    for (size_t j = 0; j < n[i].size(); ++j) {
      try {
        row.push_back(n[i][j].as<double>());
      } catch (const YAML::Exception&) {
        throw ConfigError(where + "[" + std::to_string(j) +
                          "] must be a number (got " + Shown(n[i][j]) + ")");
      }
    }
    rows.push_back(row);
  }
  return rows;
}

}  // namespace vio
