#ifndef VIO_FACTORS_VISUAL_FACTOR_OPTIONS_H_
#define VIO_FACTORS_VISUAL_FACTOR_OPTIONS_H_

// What the estimator needs to build visual factors: the feature noise and the
// robust kernel. config/visual_config.h fills it from the `visual:` block.

#include <string>

#include "factors/robust_kernel.h"

namespace vio {

struct VisualFactorOptions {
  // Standard deviation of a feature's pixel position [px] (per axis).
  double sigma_px = 1.5;
  RobustKernelOptions robust_kernel;

  // The visual factors' weight on the normalised image plane:
  // focal [px] / sigma_px, so that residuals are in units of sigma.
  double SqrtInformation(double focal_px) const { return focal_px / sigma_px; }

  // True when usable; otherwise false with a message starting with the
  // offending field ("sigma_px must be > 0 (got 0)",
  // "robust_kernel.scale must be ...").
  bool Validate(std::string* message) const;
};

}  // namespace vio

#endif  // VIO_FACTORS_VISUAL_FACTOR_OPTIONS_H_
