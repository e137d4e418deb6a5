#ifndef VIO_TOOLS_COMMAND_LINE_H_
#define VIO_TOOLS_COMMAND_LINE_H_

// What every tool's argument loop shares: walking argv, taking a flag's value
// and parsing numbers, with errors (std::invalid_argument) that name the flag.
// Each tool keeps its own flags, usage text and unknown-flag message.

#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace vio {

// Parses all of `text` as a T; throws "<flag> expects a number (got '...')".
template <typename T>
T ParseNumber(const std::string& flag, const std::string& text) {
  std::istringstream in(text);
  T value{};
  if (!(in >> value) || !in.eof()) {
    throw std::invalid_argument(flag + " expects a number (got '" + text +
                                "')");
  }
  return value;
}

class CommandLine {
 public:
  CommandLine(int argc, char** argv) : args_(argv + 1, argv + argc) {}

  // Advances to the next argument; false when there is none left.
  bool Next() { return ++index_ < args_.size(); }
  // The argument Next() advanced to.
  const std::string& Current() const { return args_[index_]; }

  // Consumes and returns the value following the current flag; throws
  // "<flag> needs a value" at the end of the line.
  std::string Value() {
    if (index_ + 1 >= args_.size()) {
      throw std::invalid_argument(Current() + " needs a value");
    }
    return args_[++index_];
  }

  // Value() parsed as a T.
  template <typename T>
  T Number() {
    const std::string flag = Current();
    return ParseNumber<T>(flag, Value());
  }

 private:
  std::vector<std::string> args_;
  size_t index_ = static_cast<size_t>(-1);  // before the first argument
};

}  // namespace vio

#endif  // VIO_TOOLS_COMMAND_LINE_H_
