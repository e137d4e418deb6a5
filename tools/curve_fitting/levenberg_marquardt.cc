#include "tools/curve_fitting/levenberg_marquardt.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace vio {

namespace {

// A value as text for error messages: "1.5", not "1.500000".
std::string FormatValue(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

constexpr double kInf = std::numeric_limits<double>::infinity();

// The weighted normal equations at one point: chi2 = sum rho(r^2),
// A = J^T W_H J, g = -J^T W_rho r (the notes' g = J^T eps, eps = -r).
struct Linearisation {
  double chi2 = kInf;
  Eigen::MatrixXd A;
  Eigen::VectorXd g;
};

bool Linearise(const ResidualFunction& residuals, const RobustKernel& kernel,
               const Eigen::VectorXd& p, Linearisation* lin) {
  Eigen::VectorXd r;
  Eigen::MatrixXd d_r_d_p;
  if (!residuals(p, &r, &d_r_d_p) || d_r_d_p.rows() != r.size() ||
      d_r_d_p.cols() != p.size() || !r.allFinite() || !d_r_d_p.allFinite()) {
    return false;
  }
  Eigen::VectorXd w_gradient(r.size());
  Eigen::VectorXd w_hessian(r.size());
  double chi2 = 0.0;
  for (Eigen::Index k = 0; k < r.size(); ++k) {
    chi2 += EvaluateKernel(kernel, r[k] * r[k]).rho;
    const IrlsWeights w = ComputeIrlsWeights(kernel, r[k]);
    w_gradient[k] = w.gradient;
    w_hessian[k] = w.hessian;
  }
  lin->chi2 = chi2;
  lin->A = d_r_d_p.transpose() * w_hessian.asDiagonal() * d_r_d_p;
  lin->g = -(d_r_d_p.transpose() * w_gradient.cwiseProduct(r));
  return std::isfinite(chi2);
}

// Solves (A + mu I) dp = g by Cholesky. False when the damped matrix is not
// numerically positive definite or the step is not finite.
bool SolveDamped(const Linearisation& lin, double mu, Eigen::VectorXd* dp) {
  Eigen::MatrixXd damped = lin.A;
  damped.diagonal().array() += mu;
  const Eigen::LLT<Eigen::MatrixXd> llt(damped);
  if (llt.info() != Eigen::Success) return false;
  *dp = llt.solve(lin.g);
  return dp->allFinite();
}

}  // namespace

bool ParseLmDamping(const std::string& name, LmDamping* damping) {
  if (name == "nielsen") {
    *damping = LmDamping::kNielsen;
  } else if (name == "marquardt") {
    *damping = LmDamping::kMarquardt;
  } else {
    return false;
  }
  return true;
}

const char* LmDampingName(LmDamping damping) {
  return damping == LmDamping::kNielsen ? "nielsen" : "marquardt";
}

const char* LmTerminationName(LmTermination termination) {
  switch (termination) {
    case LmTermination::kGradient:
      return "gradient tolerance (||g||_inf <= eps1)";
    case LmTermination::kStep:
      return "step tolerance (||dp|| <= eps2 (||p|| + eps2))";
    case LmTermination::kMaxIterations:
      return "maximum number of iterations";
    case LmTermination::kTooManyRejections:
      return "too many rejected steps in a row";
  }
  return "unknown";
}

bool LmOptions::Validate(std::string* message) const {
  auto fail = [message](const std::string& text) {
    *message = text;
    return false;
  };
  if (!(std::isfinite(tau) && tau > 0.0)) {
    return fail("tau must be finite and > 0 (got " + FormatValue(tau) + ")");
  }
  if (!(gradient_tolerance >= 0.0) || !(step_tolerance >= 0.0)) {
    return fail("gradient_tolerance and step_tolerance must be >= 0");
  }
  if (max_iterations < 1) return fail("max_iterations must be >= 1");
  if (max_rejections < 1) return fail("max_rejections must be >= 1");
  return kernel.Validate(message);
}

DampingState UpdateDamping(LmDamping damping, const DampingState& state,
                           double gain_ratio) {
  DampingState next = state;
  if (damping == LmDamping::kNielsen) {
    if (gain_ratio > 0.0) {
      const double t = 2.0 * gain_ratio - 1.0;
      next.mu = state.mu * std::max(1.0 / 3.0, 1.0 - t * t * t);
      next.nu = 2.0;
    } else {
      next.mu = state.mu * state.nu;
      next.nu = 2.0 * state.nu;
    }
  } else {
    if (gain_ratio < 0.25) {
      next.mu = 2.0 * state.mu;
    } else if (gain_ratio > 0.75) {
      next.mu = state.mu / 3.0;
    }
  }
  return next;
}

namespace {

// One iteration k of the notes: trials with growing damping until one is
// accepted. Updates *lin, *state and *summary (p, log, iterations). Returns
// true and sets summary->termination when a stopping rule fired.
bool RunIteration(const ResidualFunction& residuals, const LmOptions& options,
                  int k, Linearisation* lin, DampingState* state,
                  LmSummary* summary) {
  for (int rejections = 0;;) {
    Eigen::VectorXd dp;
    const bool solved = SolveDamped(*lin, state->mu, &dp);
    if (solved &&
        dp.norm() <= options.step_tolerance *
                         (summary->p.norm() + options.step_tolerance)) {
      summary->termination = LmTermination::kStep;
      return true;
    }
    LmTrial trial{k, kInf, state->mu, 0.0, -kInf, false};
    Linearisation trial_lin;
    if (solved &&
        Linearise(residuals, options.kernel, summary->p + dp, &trial_lin)) {
      trial.chi2 = trial_lin.chi2;
      // dp^T (mu dp + g) = 2 (L(0) - L(dp)) > 0 for any dp != 0, since
      // (A + mu I) dp = g gives L(0) - L(dp) = dp^T g - 1/2 dp^T A dp.
      trial.gain_ratio =
          (lin->chi2 - trial_lin.chi2) / dp.dot(state->mu * dp + lin->g);
    }
    trial.accepted = trial.gain_ratio > 0.0;
    *state = UpdateDamping(options.damping, *state, trial.gain_ratio);
    trial.mu_next = state->mu;
    summary->log.push_back(trial);
    if (trial.accepted) {
      summary->p += dp;
      *lin = std::move(trial_lin);
      ++summary->iterations;
      summary->termination = LmTermination::kGradient;
      return lin->g.lpNorm<Eigen::Infinity>() <= options.gradient_tolerance;
    }
    if (++rejections >= options.max_rejections) {
      summary->termination = LmTermination::kTooManyRejections;
      return true;
    }
  }
}

}  // namespace

LmSummary SolveLevenbergMarquardt(const ResidualFunction& residuals,
                                  const Eigen::VectorXd& p0,
                                  const LmOptions& options) {
  std::string message;
  if (!options.Validate(&message)) {
    throw std::invalid_argument("LmOptions: " + message);
  }
  Linearisation lin;
  if (!Linearise(residuals, options.kernel, p0, &lin)) {
    throw std::invalid_argument(
        "Levenberg-Marquardt: the residuals cannot be evaluated at the start");
  }
  LmSummary summary;
  summary.p = p0;
  summary.initial_chi2 = lin.chi2;
  DampingState state{options.tau * lin.A.diagonal().maxCoeff(), 2.0};
  summary.initial_mu = state.mu;

  summary.termination = LmTermination::kGradient;
  bool stop = lin.g.lpNorm<Eigen::Infinity>() <= options.gradient_tolerance;
  for (int k = 1; !stop && k <= options.max_iterations; ++k) {
    stop = RunIteration(residuals, options, k, &lin, &state, &summary);
  }
  if (!stop) summary.termination = LmTermination::kMaxIterations;
  summary.final_chi2 = lin.chi2;
  return summary;
}

}  // namespace vio
