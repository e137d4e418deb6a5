#ifndef VIO_FUZZ_FUZZ_INPUT_H_
#define VIO_FUZZ_FUZZ_INPUT_H_

// What every harness shares: the input handed to a parser as the file it
// reads (the parsers take paths, as they read dataset folders and configs),
// and the checks that turn a wrong outcome into a finding. A finding is an
// abort: libFuzzer saves the input and stops, like on a sanitizer report.

#include <cstddef>
#include <cstdint>
#include <string>

namespace vio::fuzz {

// A scratch file in $TMPDIR (default /tmp) named for the harness and the
// process, so parallel runs of one harness do not collide; removed at exit.
class ScratchFile {
 public:
  // `name` ends the file's name ("data.csv", "sensor.yaml").
  explicit ScratchFile(const std::string& name);
  ~ScratchFile();
  ScratchFile(const ScratchFile&) = delete;
  ScratchFile& operator=(const ScratchFile&) = delete;

  // Replaces the file's content with the input; returns the path.
  const std::string& Write(const uint8_t* data, size_t size);
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

// Aborts, printing `what`, unless `condition` holds.
void Require(bool condition, const std::string& what);

// Every input error must say which file it is about: aborts unless `message`
// starts with `file`.
void RequireNamesFile(const std::string& message, const std::string& file);

}  // namespace vio::fuzz

#endif  // VIO_FUZZ_FUZZ_INPUT_H_
