#include "fuzz/fuzz_input.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>

namespace vio::fuzz {

ScratchFile::ScratchFile(const std::string& name) {
  const char* tmp = std::getenv("TMPDIR");
  path_ = std::string(tmp != nullptr && *tmp != '\0' ? tmp : "/tmp") +
          "/tcvio_fuzz_" + std::to_string(::getpid()) + "_" + name;
}

ScratchFile::~ScratchFile() { std::remove(path_.c_str()); }

const std::string& ScratchFile::Write(const uint8_t* data, size_t size) {
  std::ofstream out(path_, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data),
            static_cast<std::streamsize>(size));
  Require(static_cast<bool>(out), "cannot write the scratch file " + path_);
  return path_;
}

void Require(bool condition, const std::string& what) {
  if (condition) return;
  std::fprintf(stderr, "fuzz finding: %s\n", what.c_str());
  std::abort();
}

void RequireNamesFile(const std::string& message, const std::string& file) {
  Require(
      message.rfind(file, 0) == 0,
      "the error does not start with the file name '" + file + "': " + message);
}

}  // namespace vio::fuzz
