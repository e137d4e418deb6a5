#ifndef VIO_TOOLS_CURVE_FITTING_LEVENBERG_MARQUARDT_H_
#define VIO_TOOLS_CURVE_FITTING_LEVENBERG_MARQUARDT_H_

// A small dense Levenberg-Marquardt solver, written out as in the user's notes
// (seeds/004, after Lourakis and Madsen-Nielsen-Tingleff), for the curve
// fitting exercise. The estimator never uses it: it always uses Ceres.
//
// Problem: minimise F(p) = 1/2 sum_k rho(r_k(p)^2) over p in R^m, with n
// scalar residuals r(p) and a robust kernel rho (robust_irls.h; rho(s) = s
// without one). With IRLS weights W_rho = diag(rho'), W_H = diag(Triggs):
//   A = J^T W_H J,  g = -J^T W_rho r          (g points downhill)
//   mu0 = tau * max_i A_ii,  nu = 2
//   solve (A + mu I) dp = g  (Cholesky, Eigen LLT)
//   gain ratio rho_g = (chi2(p) - chi2(p + dp)) / (dp^T (mu dp + g))
//   accept iff rho_g > 0, then update mu with the chosen damping strategy:
//   Nielsen:   accepted: mu *= max(1/3, 1 - (2 rho_g - 1)^3), nu = 2
//              rejected: mu *= nu, nu *= 2
//   Marquardt: rho_g < 0.25: mu *= 2;  rho_g > 0.75: mu /= 3
// where chi2 = sum_k rho(r_k^2) = 2 F. Stopping rules: ||g||_inf <= eps1,
// ||dp|| <= eps2 (||p|| + eps2), k >= k_max (k counts iterations, each of
// which ends with an accepted step; rejected trials repeat inside it).

#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "tools/curve_fitting/robust_irls.h"

namespace vio {

enum class LmDamping { kNielsen, kMarquardt };

// Parses "nielsen", "marquardt"; returns false for anything else.
bool ParseLmDamping(const std::string& name, LmDamping* damping);
const char* LmDampingName(LmDamping damping);

struct LmOptions {
  LmDamping damping = LmDamping::kNielsen;
  double tau = 1e-3;                 // mu0 = tau max diag(A) [-]
  double gradient_tolerance = 1e-6;  // eps1, on ||g||_inf [cost units]
  double step_tolerance = 1e-10;     // eps2, relative step size [-]
  int max_iterations = 100;          // k_max, accepted steps
  // Consecutive rejected trials within one iteration before giving up (a
  // guard the notes' loop lacks: with eps2 = 0 it could spin forever).
  int max_rejections = 60;
  RobustKernel kernel;  // per scalar residual

  // True when every field is in range; else false with a message naming it.
  bool Validate(std::string* message) const;
};

// Residuals r(p) (size n) and their Jacobian d_r_d_p (n x m) at p. Returns
// false when r cannot be evaluated at p (the solver then rejects the trial).
using ResidualFunction = std::function<bool(
    const Eigen::VectorXd& p, Eigen::VectorXd* r, Eigen::MatrixXd* d_r_d_p)>;

// One trial step. Trials that belong to the same iteration share k.
struct LmTrial {
  int iteration = 0;     // k of the notes, from 1
  double chi2 = 0.0;     // sum rho(r^2) at p + dp (inf if not evaluable)
  double mu = 0.0;       // damping the step was solved with
  double mu_next = 0.0;  // damping after the update
  double gain_ratio = 0.0;
  bool accepted = false;
};

enum class LmTermination {
  kGradient,          // ||g||_inf <= eps1
  kStep,              // ||dp|| <= eps2 (||p|| + eps2)
  kMaxIterations,     // k reached k_max
  kTooManyRejections  // max_rejections trials in a row failed
};
const char* LmTerminationName(LmTermination termination);

struct LmSummary {
  Eigen::VectorXd p;  // the estimate
  double initial_chi2 = 0.0;
  double final_chi2 = 0.0;
  double initial_mu = 0.0;
  int iterations = 0;        // accepted steps
  std::vector<LmTrial> log;  // every trial, in order
  LmTermination termination = LmTermination::kMaxIterations;
};

// The damping state and its update after one trial with gain ratio
// gain_ratio (accepted iff gain_ratio > 0), by the formulas above.
struct DampingState {
  double mu = 0.0;
  double nu = 2.0;  // Nielsen only
};
DampingState UpdateDamping(LmDamping damping, const DampingState& state,
                           double gain_ratio);

// Minimises from p0. Throws std::invalid_argument when the options are
// invalid or when r cannot be evaluated at p0 (the start must be valid).
LmSummary SolveLevenbergMarquardt(const ResidualFunction& residuals,
                                  const Eigen::VectorXd& p0,
                                  const LmOptions& options);

}  // namespace vio

#endif  // VIO_TOOLS_CURVE_FITTING_LEVENBERG_MARQUARDT_H_
