#ifndef VIO_TOOLS_CURVE_FITTING_ROBUST_IRLS_H_
#define VIO_TOOLS_CURVE_FITTING_ROBUST_IRLS_H_

// Robust kernels for the hand-written LM, and their IRLS weights with the
// Triggs correction (the user's notes, seeds/004: "Triggs Correction").
//
// A kernel rho(s) acts on the squared residual s = r^2 of one scalar residual;
// the robust cost is F = 1/2 sum_k rho(s_k). The kernels are defined exactly
// as Ceres' HuberLoss and CauchyLoss, so that the hand LM and Ceres minimise
// the same function:
//   none:   rho(s) = s
//   Huber:  rho(s) = s                    for s <= c^2
//                    2 c sqrt(s) - c^2    for s >  c^2
//   Cauchy: rho(s) = c^2 log(1 + s / c^2)
// The 95 % efficiency scales (for Gaussian noise of standard deviation sigma)
// are c = 1.345 sigma (Huber) and c = 2.3849 sigma (Cauchy).

#include <string>

namespace vio {

enum class KernelType { kNone, kHuber, kCauchy };

// Scales c / sigma giving 95 % asymptotic efficiency on Gaussian noise.
constexpr double kHuber95Scale = 1.345;
constexpr double kCauchy95Scale = 2.3849;

// A kernel and its scale c, in the units of the residual.
struct RobustKernel {
  KernelType type = KernelType::kNone;
  double c = 1.0;  // [residual units]; unused for kNone

  // True when c is finite and > 0 (or the kernel is kNone); else false with
  // a message naming the field.
  bool Validate(std::string* message) const;
};

// Parses "none", "huber", "cauchy"; returns false for anything else.
bool ParseKernelType(const std::string& name, KernelType* type);
const char* KernelTypeName(KernelType type);

// rho(s) and its first two derivatives with respect to s (s >= 0).
struct KernelValue {
  double rho = 0.0;
  double d_rho = 1.0;   // rho'(s)
  double d2_rho = 0.0;  // rho''(s)
};
KernelValue EvaluateKernel(const RobustKernel& kernel, double s);

// IRLS weights of one scalar residual r with Jacobian row j (the notes'
// second-order expansion of 1/2 rho(|r + j dx|^2) about dx = 0):
//   gradient:  rho' r j^T                     -> gradient = rho'(s)
//   Hessian:   j^T (rho' + 2 rho'' s) j       -> hessian  = rho' + 2 rho'' s
// The Triggs term 2 rho'' s is kept only while the Hessian weight stays
// positive; past that point (Huber's linear part, Cauchy's s > c^2) the
// residual gets the first-order IRLS weight rho' instead.
struct IrlsWeights {
  double gradient = 1.0;
  double hessian = 1.0;
};
IrlsWeights ComputeIrlsWeights(const RobustKernel& kernel, double r);

}  // namespace vio

#endif  // VIO_TOOLS_CURVE_FITTING_ROBUST_IRLS_H_
