#include "factors/visual_factor_options.h"

#include <cmath>
#include <sstream>

namespace vio {

bool VisualFactorOptions::Validate(std::string* message) const {
  if (!(std::isfinite(sigma_px) && sigma_px > 0.0)) {
    std::ostringstream out;
    out << "sigma_px must be a finite number > 0 (got " << sigma_px << ")";
    *message = out.str();
    return false;
  }
  std::string kernel_message;
  if (!robust_kernel.Validate(&kernel_message)) {
    *message = "robust_kernel." + kernel_message;
    return false;
  }
  return true;
}

}  // namespace vio
