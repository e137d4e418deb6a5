#include "estimator/gyro_aided_refinement_check.h"

#include <cmath>
#include <limits>

namespace vio {

InitFailure CheckGyroAidedRefinement(double change, double sigma,
                                     const MonoInitOptions& mono,
                                     double* value, double* limit) {
  // An unknown sigma (< 0, or not a number) fails: nothing then vouches for
  // the scale.
  if (!(sigma >= 0.0 && sigma <= mono.max_scale_uncertainty)) {
    *value = sigma;
    *limit = mono.max_scale_uncertainty;
    return InitFailure::kScaleUncertain;
  }
  const double move = change > -1.0 ? std::abs(std::log1p(change))
                                    : std::numeric_limits<double>::infinity();
  const double sigmas = move > 0.0 ? move / sigma : 0.0;
  if (!(sigmas <= mono.gyro_max_refine_change_sigmas)) {
    *value = sigmas;
    *limit = mono.gyro_max_refine_change_sigmas;
    return InitFailure::kRefinementScaleChange;
  }
  return InitFailure::kNone;
}

}  // namespace vio
