#include "tools/curve_fitting/curve_ceres.h"

#include <cmath>
#include <memory>
#include <stdexcept>

namespace vio {

bool CurveSampleCost::Evaluate(double const* const* parameters,
                               double* residuals, double** jacobians) const {
  const double* p = parameters[0];
  const double e =
      std::exp(p[kCurveA] * x_ * x_ + p[kCurveB] * x_ + p[kCurveC]);
  if (!std::isfinite(e)) return false;
  residuals[0] = e - y_;
  if (jacobians != nullptr && jacobians[0] != nullptr) {
    // d exp(u) / d p = exp(u) d u / d p with u = a x^2 + b x + c.
    jacobians[0][kCurveA] = e * x_ * x_;
    jacobians[0][kCurveB] = e * x_;
    jacobians[0][kCurveC] = e;
  }
  return true;
}

bool CeresFitOptions::Validate(std::string* message) const {
  if (max_iterations < 1) {
    *message = "max_iterations must be >= 1";
    return false;
  }
  if (!(function_tolerance >= 0.0 && gradient_tolerance >= 0.0 &&
        parameter_tolerance >= 0.0)) {
    *message = "Ceres tolerances must be >= 0";
    return false;
  }
  return kernel.Validate(message);
}

namespace {

std::unique_ptr<ceres::LossFunction> MakeLoss(const RobustKernel& kernel) {
  switch (kernel.type) {
    case KernelType::kNone:
      return nullptr;
    case KernelType::kHuber:
      return std::make_unique<ceres::HuberLoss>(kernel.c);
    case KernelType::kCauchy:
      return std::make_unique<ceres::CauchyLoss>(kernel.c);
  }
  return nullptr;
}

}  // namespace

CeresFitResult FitCurveWithCeres(const CurveSamples& samples,
                                 const Eigen::Vector3d& p0,
                                 const CeresFitOptions& options) {
  std::string message;
  if (!options.Validate(&message)) {
    throw std::invalid_argument("CeresFitOptions: " + message);
  }
  CeresFitResult result;
  result.p = p0;
  // One loss shared by every residual block, owned here.
  const std::unique_ptr<ceres::LossFunction> loss = MakeLoss(options.kernel);
  ceres::Problem::Options problem_options;
  problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  for (size_t i = 0; i < samples.x.size(); ++i) {
    problem.AddResidualBlock(new CurveSampleCost(samples.x[i], samples.y[i]),
                             loss.get(), result.p.data());
  }
  ceres::Solver::Options solver_options;
  solver_options.minimizer_type = ceres::TRUST_REGION;
  solver_options.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  solver_options.linear_solver_type = ceres::DENSE_QR;
  solver_options.max_num_iterations = options.max_iterations;
  solver_options.function_tolerance = options.function_tolerance;
  solver_options.gradient_tolerance = options.gradient_tolerance;
  solver_options.parameter_tolerance = options.parameter_tolerance;
  solver_options.num_threads = 1;
  solver_options.minimizer_progress_to_stdout = options.progress_to_stdout;
  solver_options.logging_type = options.progress_to_stdout
                                    ? ceres::PER_MINIMIZER_ITERATION
                                    : ceres::SILENT;
  ceres::Solve(solver_options, &problem, &result.summary);
  return result;
}

}  // namespace vio
