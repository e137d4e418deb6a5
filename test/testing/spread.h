#ifndef VIO_TEST_TESTING_SPREAD_H_
#define VIO_TEST_TESTING_SPREAD_H_

// The spread of a set of positions: their RMS distance from their centroid.
// A start's scale error is Spread(estimated) / Spread(true) - 1 over the same
// frames; the spread ignores the gauge (position and yaw) the two differ by.

#include <Eigen/Core>
#include <vector>

#include "estimator/scale_realignment.h"

namespace vio::testing {

inline double Spread(const std::vector<Eigen::Vector3d>& p) {
  return PositionSpread(p);  // estimator/scale_realignment.h
}

}  // namespace vio::testing

#endif  // VIO_TEST_TESTING_SPREAD_H_
