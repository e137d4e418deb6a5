// mav0/imu0/data.csv (dataset/euroc_reader.h: ReadEurocImu). A result holds
// at least one sample, every value finite, stamps strictly increasing; any
// refusal is a DatasetError naming the file.

#include <cmath>
#include <cstddef>
#include <cstdint>

#include "dataset/csv.h"
#include "dataset/euroc_reader.h"
#include "fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static vio::fuzz::ScratchFile file("imu0_data.csv");
  const std::string& path = file.Write(data, size);
  try {
    const std::vector<vio::ImuSample> samples = vio::ReadEurocImu(path);
    vio::fuzz::Require(!samples.empty(), "no sample and no error");
    for (size_t i = 0; i < samples.size(); ++i) {
      vio::fuzz::Require(
          samples[i].acc.allFinite() && samples[i].gyr.allFinite(),
          "a non-finite sample was accepted");
      vio::fuzz::Require(i == 0 || samples[i].t_ns > samples[i - 1].t_ns,
                         "stamps do not increase");
    }
  } catch (const vio::DatasetError& e) {
    vio::fuzz::RequireNamesFile(e.what(), path);
  }
  return 0;
}
