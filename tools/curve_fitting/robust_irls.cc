#include "tools/curve_fitting/robust_irls.h"

#include <cmath>
#include <sstream>

namespace vio {

namespace {

// A value as text for error messages: "1.5", not "1.500000".
std::string FormatValue(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

}  // namespace

bool RobustKernel::Validate(std::string* message) const {
  if (type != KernelType::kNone && !(std::isfinite(c) && c > 0.0)) {
    *message =
        "kernel scale c must be finite and > 0 (got " + FormatValue(c) + ")";
    return false;
  }
  return true;
}

bool ParseKernelType(const std::string& name, KernelType* type) {
  if (name == "none") {
    *type = KernelType::kNone;
  } else if (name == "huber") {
    *type = KernelType::kHuber;
  } else if (name == "cauchy") {
    *type = KernelType::kCauchy;
  } else {
    return false;
  }
  return true;
}

const char* KernelTypeName(KernelType type) {
  switch (type) {
    case KernelType::kNone:
      return "none";
    case KernelType::kHuber:
      return "huber";
    case KernelType::kCauchy:
      return "cauchy";
  }
  return "unknown";
}

KernelValue EvaluateKernel(const RobustKernel& kernel, double s) {
  KernelValue v;
  const double c2 = kernel.c * kernel.c;
  switch (kernel.type) {
    case KernelType::kNone:
      v = {s, 1.0, 0.0};
      break;
    case KernelType::kHuber:
      if (s <= c2) {
        v = {s, 1.0, 0.0};
      } else {
        // rho = 2 c s^(1/2) - c^2, rho' = c s^(-1/2), rho'' = -c/2 s^(-3/2).
        const double root = std::sqrt(s);
        v = {2.0 * kernel.c * root - c2, kernel.c / root,
             -0.5 * kernel.c / (s * root)};
      }
      break;
    case KernelType::kCauchy: {
      // rho = c^2 log(1 + s/c^2), rho' = 1 / (1 + s/c^2),
      // rho'' = -rho'^2 / c^2.
      const double d_rho = 1.0 / (1.0 + s / c2);
      v = {c2 * std::log1p(s / c2), d_rho, -d_rho * d_rho / c2};
      break;
    }
  }
  return v;
}

// Why the Triggs term is dropped where rho' + 2 rho'' s <= 0: there the
// kernel is flat or concave in r, so a Gauss-Newton model keeping the term
// would give that residual no (or negative) curvature. From the exercise's
// start at zero every residual lies beyond c, so the damped normal matrix
// would vanish and mu0 = tau max diag(J^T W J) would be 0. (Ceres' corrector
// is more conservative: it corrects only where rho'' > 0, which for Huber and
// Cauchy is nowhere.)
IrlsWeights ComputeIrlsWeights(const RobustKernel& kernel, double r) {
  const double s = r * r;
  const KernelValue v = EvaluateKernel(kernel, s);
  IrlsWeights w;
  w.gradient = v.d_rho;
  // The Hessian weight in closed form, so that Huber's linear part gives an
  // exact 0 rather than a rounding residue of c/sqrt(s) - c/sqrt(s).
  double triggs = v.d_rho;
  const double c2 = kernel.c * kernel.c;
  if (kernel.type == KernelType::kHuber) {
    triggs = s <= c2 ? 1.0 : 0.0;
  } else if (kernel.type == KernelType::kCauchy) {
    // (1 + s/c^2)^-1 - 2 s/c^2 (1 + s/c^2)^-2 = (1 - s/c^2) / (1 + s/c^2)^2.
    triggs = (1.0 - s / c2) * v.d_rho * v.d_rho;
  }
  w.hessian = triggs > 0.0 ? triggs : v.d_rho;
  return w;
}

}  // namespace vio
