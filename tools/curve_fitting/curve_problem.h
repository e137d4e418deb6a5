#ifndef VIO_TOOLS_CURVE_FITTING_CURVE_PROBLEM_H_
#define VIO_TOOLS_CURVE_FITTING_CURVE_PROBLEM_H_

// The exercise of the user's notes (seeds/001): samples of
//   y = exp(a x^2 + b x + c) + n,   n ~ N(0, sigma^2),
// at x evenly spaced in [0, 1), some optionally replaced by gross outliers,
// and the residuals of a fit of p = (a, b, c):
//   r_i(p) = exp(a x_i^2 + b x_i + c) - y_i,
//   d_r_i_d_p = exp(a x_i^2 + b x_i + c) (x_i^2, x_i, 1).

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "tools/curve_fitting/levenberg_marquardt.h"

namespace vio {

// Parameter slots of p = (a, b, c).
constexpr int kCurveA = 0, kCurveB = 1, kCurveC = 2;

struct CurveProblemOptions {
  Eigen::Vector3d truth{1.0, 2.0, 1.0};  // (a, b, c) [-]
  int num_samples = 100;                 // N, x_i = i / N
  double sigma = 1.0;                    // noise standard deviation [y units]
  uint32_t seed = 42;                    // std::mt19937 seed
  // Fraction of the samples (rounded down) that become gross outliers:
  // y_i = model + n_i + u_i sigma, u_i uniform in [min, max] (one-sided, as
  // a spurious reflection or a stuck sensor would give).
  double outlier_fraction = 0.0;     // [0, 1]
  double outlier_min_sigmas = 10.0;  // [sigma]
  double outlier_max_sigmas = 30.0;  // [sigma]

  // True when every field is in range (N >= 3, sigma >= 0, fraction in
  // [0, 1], 0 <= min <= max, everything finite); else false with a message
  // naming the field.
  bool Validate(std::string* message) const;
};

struct CurveSamples {
  std::vector<double> x;
  std::vector<double> y;
  std::vector<bool> is_outlier;
};

// y = exp(a x^2 + b x + c) for p = (a, b, c).
double CurveModel(const Eigen::Vector3d& p, double x);

// Draws the samples. Deterministic for a given options.seed. Throws
// std::invalid_argument when the options are invalid.
CurveSamples MakeCurveSamples(const CurveProblemOptions& options);

// The residual function of the fit, for SolveLevenbergMarquardt. The samples
// must outlive it. Evaluation fails (returns false) when exp overflows.
ResidualFunction CurveResiduals(const CurveSamples& samples);

// Covariance of the least-squares estimate p: (J^T J)^-1 s^2 with
// s^2 = sum r^2 / (N - 3). Returns false when J^T J is singular.
bool CurveCovariance(const CurveSamples& samples, const Eigen::Vector3d& p,
                     Eigen::Matrix3d* covariance);

}  // namespace vio

#endif  // VIO_TOOLS_CURVE_FITTING_CURVE_PROBLEM_H_
