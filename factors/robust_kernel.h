#ifndef VIO_FACTORS_ROBUST_KERNEL_H_
#define VIO_FACTORS_ROBUST_KERNEL_H_

// Robust kernels of the visual factors, chosen by configuration.
//
// The visual residuals are already whitened (in units of sigma), so the
// kernel's scale is given in units of sigma and passes straight to Ceres:
//   huber:  rho(s) = s                  for s <= c^2,  2 c sqrt(s) - c^2 else
//   cauchy: rho(s) = c^2 log(1 + s / c^2)
// with s = |r|^2. Defaults (the user's notes): Huber c = 1.345 and Cauchy
// c = 2.3849, the scales with 95 % efficiency on Gaussian residuals.

#include <ceres/loss_function.h>

#include <memory>
#include <string>

namespace vio {

enum class RobustKernelType { kNone, kHuber, kCauchy };

constexpr double kDefaultHuberScale = 1.345;    // [sigma]
constexpr double kDefaultCauchyScale = 2.3849;  // [sigma]

struct RobustKernelOptions {
  RobustKernelType type = RobustKernelType::kHuber;
  double scale = kDefaultHuberScale;  // [sigma]; ignored for kNone

  // True when usable; otherwise false with a message that starts with the
  // offending field's name ("scale must be > 0 (got -1)").
  bool Validate(std::string* message) const;
};

// "none", "huber", "cauchy" <-> RobustKernelType. ParseRobustKernelType
// returns false for any other text.
const char* RobustKernelName(RobustKernelType type);
bool ParseRobustKernelType(const std::string& text, RobustKernelType* type);

// The default scale of a kernel type [sigma] (0 for kNone).
double DefaultRobustKernelScale(RobustKernelType type);

// A new ceres::HuberLoss or ceres::CauchyLoss with options.scale, or nullptr
// for kNone (Ceres' plain squared loss). Hand it to Problem::AddResidualBlock,
// which takes ownership (release() it). Throws std::invalid_argument when
// options do not validate.
std::unique_ptr<ceres::LossFunction> MakeLossFunction(
    const RobustKernelOptions& options);

}  // namespace vio

#endif  // VIO_FACTORS_ROBUST_KERNEL_H_
