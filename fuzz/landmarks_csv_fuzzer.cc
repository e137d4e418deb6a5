// landmarks.csv, a run's mapped landmarks (dataset/landmarks_io.h:
// ReadLandmarksCsv). What reads is finite; any refusal is a DatasetError
// naming the file.

#include <cmath>
#include <cstddef>
#include <cstdint>

#include "dataset/csv.h"
#include "dataset/landmarks_io.h"
#include "fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static vio::fuzz::ScratchFile file("landmarks.csv");
  const std::string& path = file.Write(data, size);
  try {
    for (const vio::LandmarkRow& row : vio::ReadLandmarksCsv(path)) {
      vio::fuzz::Require(row.p_w.allFinite() && std::isfinite(row.parallax_deg),
                         "a non-finite landmark was accepted");
    }
  } catch (const vio::DatasetError& e) {
    vio::fuzz::RequireNamesFile(e.what(), path);
  }
  return 0;
}
