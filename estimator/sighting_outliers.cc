#include "estimator/sighting_outliers.h"

#include <cmath>

namespace vio {

SightingVerdict ClassifySightings(const std::vector<double>& errors,
                                  double threshold) {
  SightingVerdict v;
  for (size_t i = 0; i < errors.size(); ++i) {
    if (!std::isfinite(errors[i])) {
      v.whole = true;
      v.bad.clear();
      return v;
    }
    if (errors[i] > threshold) v.bad.push_back(static_cast<int>(i));
  }
  if (2 * v.bad.size() > errors.size()) {
    v.whole = true;
    v.bad.clear();
  }
  return v;
}

}  // namespace vio
