#ifndef VIO_TEST_TESTING_SPREAD_H_
#define VIO_TEST_TESTING_SPREAD_H_

// The spread of a set of positions: their RMS distance from their centroid.
// A start's scale error is Spread(estimated) / Spread(true) - 1 over the same
// frames; the spread ignores the gauge (position and yaw) the two differ by.

#include <Eigen/Core>
#include <cmath>
#include <vector>

namespace vio::testing {

inline double Spread(const std::vector<Eigen::Vector3d>& p) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& x : p) c += x;
  c /= static_cast<double>(p.size());
  double s = 0.0;
  for (const Eigen::Vector3d& x : p) s += (x - c).squaredNorm();
  return std::sqrt(s / static_cast<double>(p.size()));
}

}  // namespace vio::testing

#endif  // VIO_TEST_TESTING_SPREAD_H_
