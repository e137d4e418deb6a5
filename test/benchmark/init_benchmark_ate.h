#ifndef VIO_TEST_BENCHMARK_INIT_BENCHMARK_ATE_H_
#define VIO_TEST_BENCHMARK_INIT_BENCHMARK_ATE_H_

// init_benchmark --ate: the end-to-end target (docs/
// initialisation.md, "End to end"), each in-motion run's ATE against the
// same motion started from rest, over --ate-runs runs per preset (seeds
// 2000 on, start phases spread over a lap).

#include <string>

#include "test/benchmark/init_benchmark_args.h"

namespace vio {

// The same sequence (the default): ONE simulation that starts at rest (2 s
// still, a 2 s blend, then the preset's motion) replayed whole (from rest)
// and cut at a moving instant t0 after the blend (in motion: the identical
// IMU samples and tracks from t0 on; t0 = 5, 6.5, 8, 9.5 s in turn, or
// --cut S), so the two runs differ only by their start. Both ATEs are taken
// on the frames from the in-motion run's first estimate on, and from t0 + S
// for each --ate-from S, each run aligned on those frames alone.
void SameSequenceAte(const std::string& preset, const Args& args);

// --ate-separate: two simulations, the preset as it is (in motion) and
// another of the same motion after a 2 s still start and a 2 s blend, with
// its own noise on other parts of the lap; whole-run ATEs, and from the
// first frame + S for each --ate-from S.
void SeparateSimulationsAte(const std::string& preset, const Args& args);

}  // namespace vio

#endif  // VIO_TEST_BENCHMARK_INIT_BENCHMARK_ATE_H_
