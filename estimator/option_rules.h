#pragma once

// The checks behind the options' Validate(): each rule names its field the
// way its YAML key reads, and the first one violated is the message.

#include <cmath>
#include <sstream>
#include <string>

namespace vio {

class OptionRules {
 public:
  void Positive(const char* name, double value) {
    Require(std::isfinite(value) && value > 0.0, name, value, "must be > 0");
  }
  void NonNegative(const char* name, double value) {
    Require(std::isfinite(value) && value >= 0.0, name, value, "must be >= 0");
  }
  void AtLeast(const char* name, double value, double low) {
    std::ostringstream rule;
    rule << "must be >= " << low;
    Require(std::isfinite(value) && value >= low, name, value, rule.str());
  }
  void Finite(const char* name, double value) {
    Require(std::isfinite(value), name, value, "must be finite");
  }
  void Require(bool ok, const char* name, double value,
               const std::string& rule) {
    if (ok || !message_.empty()) return;
    std::ostringstream out;
    out << name << " " << rule << " (got " << value << ")";
    message_ = out.str();
  }
  // A sub-struct's own Validate() result, its message prefixed.
  void Nested(const char* prefix, bool ok, const std::string& message) {
    if (ok || !message_.empty()) return;
    message_ = prefix + message;
  }
  // True when no rule was violated; otherwise the first violation in *message.
  bool Done(std::string* message) const {
    if (message_.empty()) return true;
    *message = message_;
    return false;
  }

 private:
  std::string message_;
};

}  // namespace vio
