// mav0/camN/features.csv (dataset/features_csv.h: ReadFeaturesCsv). A result
// has frames in increasing stamp order, each with its observations' ids
// >= 0 and unique, pixels finite; any refusal is a DatasetError naming the
// file.

#include <cstddef>
#include <cstdint>
#include <set>

#include "dataset/csv.h"
#include "dataset/features_csv.h"
#include "fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static vio::fuzz::ScratchFile file("features.csv");
  const std::string& path = file.Write(data, size);
  try {
    const std::vector<vio::FeatureFrame> frames = vio::ReadFeaturesCsv(path, 1);
    for (size_t i = 0; i < frames.size(); ++i) {
      vio::fuzz::Require(i == 0 || frames[i].t_ns > frames[i - 1].t_ns,
                         "frame stamps do not increase");
      vio::fuzz::Require(!frames[i].observations.empty(), "an empty frame");
      std::set<int64_t> ids;
      for (const vio::FeatureObservation& o : frames[i].observations) {
        vio::fuzz::Require(
            o.camera == 1 && o.feature_id >= 0 && o.uv.allFinite(),
            "a bad observation was accepted");
        vio::fuzz::Require(ids.insert(o.feature_id).second,
                           "an id repeated within a frame");
      }
    }
  } catch (const vio::DatasetError& e) {
    vio::fuzz::RequireNamesFile(e.what(), path);
  }
  return 0;
}
