#pragma once

// CPU time of the calling thread [s]: what a step of the estimator costs,
// whatever else runs on the machine (the solver's and the marginalisation's
// figures in the summary).

#include <time.h>

namespace vio {

inline double ThreadCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

}  // namespace vio
