// mav0/state_groundtruth_estimate0/data.csv, the dataset's ground truth
// (dataset/trajectory_io.h: ReadEurocGroundTruth). A result has strictly
// increasing stamps, unit quaternions and finite values; any refusal is a
// DatasetError naming the file.

#include <cmath>
#include <cstddef>
#include <cstdint>

#include "dataset/csv.h"
#include "dataset/trajectory_io.h"
#include "fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static vio::fuzz::ScratchFile file("groundtruth.csv");
  const std::string& path = file.Write(data, size);
  try {
    const std::vector<vio::StampedState> states =
        vio::ReadEurocGroundTruth(path);
    vio::fuzz::Require(!states.empty(), "no state and no error");
    for (size_t i = 0; i < states.size(); ++i) {
      const vio::StampedState& s = states[i];
      vio::fuzz::Require(i == 0 || s.t_ns > states[i - 1].t_ns,
                         "stamps do not strictly increase");
      vio::fuzz::Require(std::abs(s.q_w_b.norm() - 1.0) < 1e-9,
                         "a quaternion is not normalised");
      vio::fuzz::Require(s.p_w_b.allFinite() && s.v_w.allFinite() &&
                             s.b_a.allFinite() && s.b_g.allFinite(),
                         "a non-finite value was accepted");
    }
  } catch (const vio::DatasetError& e) {
    vio::fuzz::RequireNamesFile(e.what(), path);
  }
  return 0;
}
