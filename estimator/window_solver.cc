#include "estimator/window_solver.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>

#include "estimator/window_linearization.h"

namespace vio {
namespace {

using Clock = std::chrono::steady_clock;

double Since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Ceres' trust-region constants (TrustRegionStrategy, DoglegStrategy).
constexpr double kMaxRadius = 1e16;
constexpr double kMinRadius = 1e-32;
constexpr double kMinMu = 1e-8;  // Gauss-Newton regularisation of the dogleg
constexpr double kMaxMu = 1.0;
constexpr double kMuIncrease = 10.0;

// Powell's dogleg in the Jacobi-scaled space x_s = D x, D_i = 1 + sqrt(A_ii)
// (Ceres scales the Jacobian's columns by 1 / D_i): the trust region is the
// ball |D dx| <= radius. The Gauss-Newton step and the Cauchy point depend on
// the linearisation only, so a rejected step re-uses them.
class Dogleg {
 public:
  // Gauss-Newton step and Cauchy point at the current linearisation;
  // kept_factor: solved by WindowLinearization::SolveDampedWithKeptFactor.
  void Linearized(WindowLinearization* lin, bool kept_factor) {
    D_ = (1.0 + lin->jtj_diagonal().array().max(0.0).sqrt()).matrix();
    const Eigen::VectorXd& g = lin->gradient();
    g_s_ = g.cwiseQuotient(D_);
    // Cauchy point: the model's minimum along -g_s, alpha = |g_s|^2 /
    // |J_s g_s|^2 with J_s g_s = J (g / D^2).
    const double g_s_sq = g_s_.squaredNorm();
    const double curvature =
        lin->QuadraticForm(g.cwiseQuotient(D_.cwiseAbs2()));
    alpha_ = curvature > 0.0 ? g_s_sq / curvature : 0.0;
    // Gauss-Newton with a small regularisation, raised while the reduced
    // system is not positive definite (as Ceres' mu).
    gn_ok_ = false;
    for (; mu_ <= kMaxMu; mu_ *= kMuIncrease) {
      if (kept_factor ? lin->SolveDampedWithKeptFactor(mu_, &gauss_newton_)
                      : lin->SolveDamped(mu_, &gauss_newton_)) {
        gn_ok_ = true;
        mu_ = std::max(kMinMu, 2.0 * mu_ / kMuIncrease);
        break;
      }
    }
    if (!gn_ok_) mu_ = kMinMu;
  }

  // The dogleg step for the radius; returns false when there is none (no
  // gradient). *scaled_norm receives |D dx|.
  bool Step(double radius, Eigen::VectorXd* dx, double* scaled_norm) const {
    const double g_norm = g_s_.norm();
    if (gn_ok_) {
      const Eigen::VectorXd gn_s = D_.cwiseProduct(gauss_newton_);
      const double gn_norm = gn_s.norm();
      if (gn_norm <= radius) {
        *dx = gauss_newton_;
        *scaled_norm = gn_norm;
        return true;
      }
      const double cauchy_norm = alpha_ * g_norm;
      if (cauchy_norm < radius && alpha_ > 0.0) {
        // Between the Cauchy point a and the Gauss-Newton step b: the point
        // a + beta (b - a) on the sphere, beta in [0, 1] (the stable root of
        // |a + beta d|^2 = radius^2, d = b - a).
        const Eigen::VectorXd a = -alpha_ * g_s_;
        const Eigen::VectorXd d = gn_s - a;
        const double c = a.dot(d);
        const double dd = d.squaredNorm();
        const double e = a.squaredNorm() - radius * radius;
        const double root = std::sqrt(std::max(c * c - dd * e, 0.0));
        const double beta = c <= 0.0 ? (-c + root) / dd : -e / (c + root);
        *dx = (a + beta * d).cwiseQuotient(D_);
        *scaled_norm = radius;
        return dx->allFinite();
      }
    }
    if (!(g_norm > 0.0)) return false;
    // The Cauchy direction, cut at the radius (or at the Cauchy point).
    const double length =
        alpha_ > 0.0 ? std::min(alpha_ * g_norm, radius) : radius;
    *dx = (-(length / g_norm) * g_s_).cwiseQuotient(D_);
    *scaled_norm = length;
    return dx->allFinite();
  }

 private:
  Eigen::VectorXd D_, g_s_, gauss_newton_;
  double alpha_ = 0.0;
  double mu_ = kMinMu;
  bool gn_ok_ = false;
};

ceres::IterationSummary Iteration(int k, double cost) {
  ceres::IterationSummary it;
  it.iteration = k;
  it.cost = cost;
  return it;
}

}  // namespace

WindowSolver::WindowSolver()
    : linearization_(std::make_unique<WindowLinearization>()) {}

WindowSolver::~WindowSolver() = default;
WindowSolver::WindowSolver(WindowSolver&&) noexcept = default;
WindowSolver& WindowSolver::operator=(WindowSolver&&) noexcept = default;

ceres::Solver::Summary SolveWindow(const WindowSolverProblem& problem,
                                   const WindowSolverOptions& options) {
  WindowSolver solver;
  *solver.NewProblem() = problem;
  return solver.Solve(options);
}

ceres::Solver::Summary WindowSolver::Solve(const WindowSolverOptions& options) {
  ceres::Solver::Summary summary;
  // Ceres' Summary starts its times at -1 (not measured).
  summary.preprocessor_time_in_seconds = 0.0;
  summary.minimizer_time_in_seconds = 0.0;
  summary.postprocessor_time_in_seconds = 0.0;
  summary.total_time_in_seconds = 0.0;
  summary.linear_solver_time_in_seconds = 0.0;
  summary.residual_evaluation_time_in_seconds = 0.0;
  summary.jacobian_evaluation_time_in_seconds = 0.0;
  summary.inner_iteration_time_in_seconds = 0.0;
  summary.line_search_cost_evaluation_time_in_seconds = 0.0;
  summary.line_search_gradient_evaluation_time_in_seconds = 0.0;
  summary.line_search_polynomial_minimization_time_in_seconds = 0.0;
  summary.line_search_total_time_in_seconds = 0.0;
  summary.linear_solver_type_given = ceres::DENSE_SCHUR;
  summary.linear_solver_type_used = ceres::DENSE_SCHUR;
  summary.trust_region_strategy_type = options.trust_region;
  const Clock::time_point start = Clock::now();
  WindowLinearization& lin = *linearization_;
  lin.SetUp(problem_);
  summary.preprocessor_time_in_seconds = Since(start);
  auto finish = [&](ceres::TerminationType type, const std::string& message) {
    summary.termination_type = type;
    summary.message = message;
    summary.total_time_in_seconds = Since(start);
    return summary;
  };

  Clock::time_point t = Clock::now();
  bool ok = lin.Linearize();
  summary.jacobian_evaluation_time_in_seconds += Since(t);
  if (!ok) {
    return finish(ceres::FAILURE,
                  "residual and Jacobian evaluation failed at the start");
  }
  double cost = lin.cost();
  summary.initial_cost = summary.final_cost = cost;
  summary.iterations.push_back(Iteration(0, cost));
  summary.iterations.back().gradient_max_norm = lin.ProjectedGradientMaxNorm();
  if (summary.iterations.back().gradient_max_norm <=
      options.gradient_tolerance) {
    return finish(ceres::CONVERGENCE, "gradient tolerance reached");
  }
  const bool lm = options.trust_region == ceres::LEVENBERG_MARQUARDT;
  double radius = options.initial_trust_region_radius;
  double nu = 2.0;  // Nielsen's factor for a rejected LM step
  Dogleg dogleg;
  if (!lm) {
    t = Clock::now();
    dogleg.Linearized(&lin, options.kept_factor_pcg);
    summary.linear_solver_time_in_seconds += Since(t);
  }
  Eigen::VectorXd dx;
  for (int k = 1;; ++k) {
    if (k > options.max_iterations) {
      return finish(ceres::NO_CONVERGENCE, "maximum number of iterations");
    }
    if (options.max_time_s > 0.0 && Since(start) > options.max_time_s) {
      return finish(ceres::NO_CONVERGENCE, "time limit");
    }
    ceres::IterationSummary it = Iteration(k, cost);
    it.trust_region_radius = radius;
    t = Clock::now();
    double scaled_norm = 0.0;
    const bool have_step =
        !lm ? dogleg.Step(radius, &dx, &scaled_norm)
        : options.kept_factor_pcg
            ? lin.SolveDampedWithKeptFactor(1.0 / radius, &dx)
            : lin.SolveDamped(1.0 / radius, &dx);
    summary.linear_solver_time_in_seconds += Since(t);
    double new_cost = std::numeric_limits<double>::infinity();
    double model_decrease = 0.0;
    if (have_step) {
      it.step_norm = dx.norm();
      if (it.step_norm <= options.parameter_tolerance *
                              (lin.StateNorm() + options.parameter_tolerance)) {
        summary.iterations.push_back(it);
        return finish(ceres::CONVERGENCE, "parameter tolerance reached");
      }
      // The model's decrease -(g.dx + |J dx|^2 / 2): the Gauss-Newton model
      // of the cost, whatever the step.
      model_decrease = -(lin.gradient().dot(dx) + 0.5 * lin.QuadraticForm(dx));
      t = Clock::now();
      if (!lin.CandidateCost(dx, &new_cost)) {
        new_cost = std::numeric_limits<double>::infinity();
      }
      summary.residual_evaluation_time_in_seconds += Since(t);
    }
    it.step_is_valid = have_step && model_decrease > 0.0;
    it.relative_decrease =
        it.step_is_valid ? (cost - new_cost) / model_decrease : 0.0;
    it.step_is_successful =
        it.step_is_valid &&
        it.relative_decrease > options.min_relative_decrease;
    if (!it.step_is_successful) {
      radius = lm ? radius / nu : 0.5 * radius;
      nu *= 2.0;
      summary.iterations.push_back(it);
      if (radius < kMinRadius) {
        return finish(ceres::CONVERGENCE, "minimum trust region radius");
      }
      continue;
    }
    const double rho = it.relative_decrease;
    if (lm) {
      radius = radius / std::max(1.0 / 3.0, 1.0 - std::pow(2.0 * rho - 1.0, 3));
      nu = 2.0;
    } else if (rho > 0.75) {
      radius = std::max(radius, 3.0 * scaled_norm);
    } else if (rho < 0.25) {
      radius *= 0.5;
    }
    radius = std::min(radius, kMaxRadius);
    lin.Accept();
    const double old_cost = cost;
    cost = summary.final_cost = new_cost;
    it.cost = cost;
    it.cost_change = old_cost - cost;
    // Stopping here needs no Jacobians at the new point (Ceres evaluates
    // them after every accepted step; that is one evaluation per step saved).
    if (std::abs(it.cost_change) <= options.function_tolerance * old_cost) {
      summary.iterations.push_back(it);
      return finish(ceres::CONVERGENCE, "function tolerance reached");
    }
    if (k == options.max_iterations) {
      summary.iterations.push_back(it);
      return finish(ceres::NO_CONVERGENCE, "maximum number of iterations");
    }
    t = Clock::now();
    ok = lin.Linearize();
    summary.jacobian_evaluation_time_in_seconds += Since(t);
    if (!ok) {
      summary.iterations.push_back(it);
      return finish(ceres::FAILURE,
                    "residual and Jacobian evaluation failed after a step");
    }
    cost = summary.final_cost = lin.cost();
    it.gradient_max_norm = lin.ProjectedGradientMaxNorm();
    summary.iterations.push_back(it);
    if (it.gradient_max_norm <= options.gradient_tolerance) {
      return finish(ceres::CONVERGENCE, "gradient tolerance reached");
    }
    if (!lm) {
      t = Clock::now();
      dogleg.Linearized(&lin, options.kept_factor_pcg);
      summary.linear_solver_time_in_seconds += Since(t);
    }
  }
}

}  // namespace vio
