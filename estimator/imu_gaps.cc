#include "estimator/imu_gaps.h"

#include <algorithm>

namespace vio {

int64_t LongestImuHoleNs(const std::vector<ImuSample>& imu, int64_t t0_ns,
                         int64_t t1_ns) {
  if (imu.empty()) return t1_ns - t0_ns;
  const auto before = [](int64_t t, const ImuSample& s) { return t < s.t_ns; };
  const auto after = [](const ImuSample& s, int64_t t) { return s.t_ns < t; };
  // lo: the last sample at or before t0; hi: the first at or after t1.
  auto lo = std::upper_bound(imu.begin(), imu.end(), t0_ns, before);
  const auto hi = std::lower_bound(imu.begin(), imu.end(), t1_ns, after);
  int64_t longest = 0;
  if (lo == imu.begin()) {
    longest = imu.front().t_ns - t0_ns;
  } else {
    --lo;
  }
  if (hi == imu.end()) longest = std::max(longest, t1_ns - imu.back().t_ns);
  const auto last = hi == imu.end() ? imu.end() - 1 : hi;
  for (auto it = lo; it < last; ++it) {
    longest = std::max(longest, (it + 1)->t_ns - it->t_ns);
  }
  return longest;
}

}  // namespace vio
