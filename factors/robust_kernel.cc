#include "factors/robust_kernel.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace vio {

bool RobustKernelOptions::Validate(std::string* message) const {
  if (type == RobustKernelType::kNone) return true;
  if (!(std::isfinite(scale) && scale > 0.0)) {
    std::ostringstream out;
    out << "scale must be a finite number > 0 (got " << scale << ")";
    *message = out.str();
    return false;
  }
  return true;
}

const char* RobustKernelName(RobustKernelType type) {
  switch (type) {
    case RobustKernelType::kNone:
      return "none";
    case RobustKernelType::kHuber:
      return "huber";
    case RobustKernelType::kCauchy:
      return "cauchy";
  }
  return "none";
}

bool ParseRobustKernelType(const std::string& text, RobustKernelType* type) {
  for (RobustKernelType t : {RobustKernelType::kNone, RobustKernelType::kHuber,
                             RobustKernelType::kCauchy}) {
    if (text == RobustKernelName(t)) {
      *type = t;
      return true;
    }
  }
  return false;
}

double DefaultRobustKernelScale(RobustKernelType type) {
  switch (type) {
    case RobustKernelType::kNone:
      return 0.0;
    case RobustKernelType::kHuber:
      return kDefaultHuberScale;
    case RobustKernelType::kCauchy:
      return kDefaultCauchyScale;
  }
  return 0.0;
}

std::unique_ptr<ceres::LossFunction> MakeLossFunction(
    const RobustKernelOptions& options) {
  std::string message;
  if (!options.Validate(&message)) {
    throw std::invalid_argument("robust kernel: " + message);
  }
  // Ceres' parameter a is the scale in the residual's own units; ours are
  // units of sigma, so the configured scale is passed as it is.
  switch (options.type) {
    case RobustKernelType::kNone:
      return nullptr;
    case RobustKernelType::kHuber:
      return std::make_unique<ceres::HuberLoss>(options.scale);
    case RobustKernelType::kCauchy:
      return std::make_unique<ceres::CauchyLoss>(options.scale);
  }
  return nullptr;
}

}  // namespace vio
