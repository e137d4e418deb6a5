// A TUM trajectory file (t x y z qx qy qz qw, t in seconds), read by
// dataset/trajectory_io.h: ReadTum. An accepted file gives a valid trajectory
// (fuzz/trajectory_checks.h); any refusal is a DatasetError naming the file.

#include <cstddef>
#include <cstdint>

#include "dataset/csv.h"
#include "dataset/trajectory_io.h"
#include "fuzz/fuzz_input.h"
#include "fuzz/trajectory_checks.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static vio::fuzz::ScratchFile file("estimate.tum");
  const std::string& path = file.Write(data, size);
  try {
    vio::fuzz::RequireValidTrajectory(vio::ReadTum(path));
  } catch (const vio::DatasetError& e) {
    vio::fuzz::RequireNamesFile(e.what(), path);
  }
  return 0;
}
