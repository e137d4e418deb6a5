#include "eval/pixel_errors.h"

#include <algorithm>
#include <cmath>

namespace vio {

PixelErrorStats ComputePixelErrorStats(std::vector<double> e) {
  PixelErrorStats s;
  s.count = e.size();
  if (e.empty()) return s;
  std::sort(e.begin(), e.end());
  const size_t n = e.size();
  s.median = n % 2 == 1 ? e[n / 2] : 0.5 * (e[n / 2 - 1] + e[n / 2]);
  const size_t rank = static_cast<size_t>(std::ceil(0.95 * n));
  s.p95 = e[std::max<size_t>(rank, 1) - 1];
  s.max = e.back();
  double sum = 0.0;
  size_t over1 = 0, over3 = 0;
  for (const double v : e) {
    sum += v;
    if (v > 1.0) ++over1;
    if (v > 3.0) ++over3;
  }
  s.mean = sum / n;
  s.share_over_1px = static_cast<double>(over1) / n;
  s.share_over_3px = static_cast<double>(over3) / n;
  return s;
}

}  // namespace vio
