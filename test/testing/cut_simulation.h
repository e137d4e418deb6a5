#ifndef VIO_TEST_TESTING_CUT_SIMULATION_H_
#define VIO_TEST_TESTING_CUT_SIMULATION_H_

// A simulation cut at a moving instant, as a user trims a recorded sequence:
// the same IMU samples, camera frames (uv, feature ids, outlier flags) and
// truth from t0 on, nothing before. Replaying the cut against replaying the
// whole compares two starts on one noise realisation (docs/
// initialisation.md, "End to end").

#include <cstdint>

#include "dataset/simulator.h"

namespace vio {
namespace testing {

// The samples, frames and truth of `simulation` with stamps >= t0_ns (camera
// stamps for the frames), unchanged; options.start_time_ns becomes the first
// kept IMU stamp and duration_s the kept span; the summary's counts are of
// the kept part. The frames keep their raw uv only (xy and velocity are
// the observation builder's, to be made again on the cut: a trimmed folder's
// first frame has no previous one). Throws std::invalid_argument when t0_ns
// leaves fewer than two IMU samples or no frame.
Simulation CutSimulation(const Simulation& simulation, int64_t t0_ns);

}  // namespace testing
}  // namespace vio

#endif  // VIO_TEST_TESTING_CUT_SIMULATION_H_
