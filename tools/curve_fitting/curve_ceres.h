#ifndef VIO_TOOLS_CURVE_FITTING_CURVE_CERES_H_
#define VIO_TOOLS_CURVE_FITTING_CURVE_CERES_H_

// The Ceres side of the curve fitting exercise: one analytic-Jacobian cost
// function per sample and a fit with Ceres' own Levenberg-Marquardt, with
// ceres::HuberLoss / ceres::CauchyLoss for the robust runs (the same kernels
// as robust_irls.h, so both solvers minimise the same cost).

#include <ceres/ceres.h>

#include <Eigen/Core>
#include <string>

#include "tools/curve_fitting/curve_problem.h"
#include "tools/curve_fitting/robust_irls.h"

namespace vio {

// Residual of one sample (x, y), with one parameter block p = (a, b, c):
//   r = exp(a x^2 + b x + c) - y                       (1)
//   d_r_d_p = exp(a x^2 + b x + c) (x^2, x, 1)          (1 x 3)
// p is Euclidean. Evaluate returns false when exp overflows.
class CurveSampleCost final : public ceres::SizedCostFunction<1, 3> {
 public:
  CurveSampleCost(double x, double y) : x_(x), y_(y) {}

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  double x_;  // abscissa [-]
  double y_;  // measured ordinate [y units]
};

struct CeresFitOptions {
  RobustKernel kernel;
  int max_iterations = 100;
  // Ceres' convergence tolerances, tight so that both solvers run to the
  // bottom of the same minimum.
  double function_tolerance = 1e-15;   // relative cost change [-]
  double gradient_tolerance = 1e-15;   // relative gradient max-norm [-]
  double parameter_tolerance = 1e-12;  // relative step size [-]
  // Let Ceres print its own per-iteration log to stdout. Only tools set it:
  // library code never prints.
  bool progress_to_stdout = false;

  // True when every field is in range; else false with a message naming it.
  bool Validate(std::string* message) const;
};

struct CeresFitResult {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();  // (a, b, c)
  ceres::Solver::Summary summary;
};

// Fits (a, b, c) from p0 with ceres::LEVENBERG_MARQUARDT and DENSE_QR.
// Throws std::invalid_argument when the options are invalid.
CeresFitResult FitCurveWithCeres(const CurveSamples& samples,
                                 const Eigen::Vector3d& p0,
                                 const CeresFitOptions& options);

}  // namespace vio

#endif  // VIO_TOOLS_CURVE_FITTING_CURVE_CERES_H_
