#ifndef VIO_ESTIMATOR_WINDOW_SOLVER_H_
#define VIO_ESTIMATOR_WINDOW_SOLVER_H_

// The nonlinear least-squares solver of one window step, written for the
// window's structure:
//
//   minimise  1/2 sum_i rho_i(|r_i(x)|^2)
//
// over the window's blocks, with Ceres' own cost functions, manifolds and
// loss functions as the model (so every factor, the pose manifold and the
// robust kernels are exactly what ceres::Solve would use), but its own
// iteration. Why not ceres::Solve: on this problem (about 1000 small residual
// blocks, 120 one-dimensional inverse depths, 10 frames) most of Ceres' time
// went to per-step preprocessing, per-block bookkeeping and a Schur eliminator
// built for dynamic block sizes (the Debian build has no specialisation for
// one-dimensional landmarks); docs/speed.md has the profile.
//
// Structure used:
//   - every "eliminated" block (an inverse depth: Euclidean, size 1, no
//     residual touches two of them) is removed by its Schur complement,
//     which for a scalar is a rank-one update per landmark:
//        H_rr -= w w^T / h,   g_r -= w g_l / h,
//     with h = sum J_l^T J_l, g_l = sum J_l^T r, w = sum J_r^T J_l over the
//     landmark's residuals;
//   - the remaining ("reduced") blocks (poses, speed-biases, extrinsics,
//     t_d) form one dense symmetric system, solved by Cholesky (Eigen LLT);
//   - the inverse depths follow by back substitution,
//        dx_l = -(g_l + w^T dx_r) / h.
// Each residual's tangent Jacobian is J_ambient * PlusJacobian(x) (what Ceres
// uses), and robust losses enter through Ceres' Corrector rule (Triggs
// correction where rho'' > 0, sqrt(rho') scaling otherwise).
//
// Steps: Levenberg-Marquardt (D = diag(J^T J), radius update of Nielsen, as
// Ceres' LEVENBERG_MARQUARDT) or Powell's dogleg (traditional dogleg in the
// Jacobi-scaled space, as Ceres' DOGLEG; a rejected step re-uses the
// Gauss-Newton and Cauchy steps). Stops as Ceres does, with Ceres' default
// tolerances: function (relative cost change 1e-6), gradient (1e-10),
// parameter (relative step 1e-8), the iteration limit, a wall-clock budget.
// Bounds (Euclidean blocks) are enforced by projecting the candidate, as
// Ceres' ParameterBlock::Plus does.
//
// Determinism: one thread, every sum in a fixed order (residuals in the
// order given): the same input gives the same output bit for bit.

#include <ceres/cost_function.h>
#include <ceres/loss_function.h>
#include <ceres/manifold.h>
#include <ceres/solver.h>
#include <ceres/types.h>

#include <limits>
#include <memory>
#include <vector>

#include "factors/marginalization_prior.h"
#include "factors/tangent_jacobians.h"

namespace vio {

struct WindowSolverBlock {
  double* values = nullptr;  // ambient values, updated in place (not owned)
  int size = 0;              // ambient size
  const ceres::Manifold* manifold = nullptr;  // nullptr: Euclidean
  bool constant = false;
  // Solved in closed form through its Schur complement: requires a
  // Euclidean, non-constant block of size 1 and that no residual touches two
  // eliminated blocks (inverse depths).
  bool eliminated = false;
  // Bounds on every coordinate of a Euclidean block.
  double lower = -std::numeric_limits<double>::infinity();
  double upper = std::numeric_limits<double>::infinity();
};

struct WindowSolverResidual {
  const ceres::CostFunction* cost = nullptr;  // not owned
  const ceres::LossFunction* loss = nullptr;  // nullptr: squared loss
  // Its blocks, in cost order: WindowSolverProblem::block_indices
  // [first_block, first_block + num_blocks), indices into the block list.
  int first_block = 0;
  int num_blocks = 0;
  // Set when cost is a marginalisation prior (the same object): its normal
  // equations then come from its stored J^T J (MarginalizationPrior::
  // information), a few 3 x 3 products instead of a dense n x n' Jacobian
  // product per iteration. Its blocks must not be eliminated.
  const MarginalizationPrior* prior = nullptr;
  // Set when cost also gives its Jacobians in the tangent space (the same
  // object): they are then taken as they are, without the lift to the
  // ambient space and the PlusJacobian product that undoes it.
  const TangentJacobians* tangent = nullptr;
};

struct WindowSolverOptions {
  ceres::TrustRegionStrategyType trust_region = ceres::DOGLEG;
  int max_iterations = 4;   // steps, accepted or not [-]
  double max_time_s = 0.0;  // wall-clock budget [s]; 0: none
  // Ceres' defaults.
  double function_tolerance = 1e-6;   // |cost change| / cost [-]
  double gradient_tolerance = 1e-10;  // max |gradient| [-]
  double parameter_tolerance = 1e-8;  // |step| / (|x| + tol) [-]
  double initial_trust_region_radius = 1e4;
  double min_relative_decrease = 1e-3;  // rho below this: step rejected
  // Off: every linearisation's reduced system is factored (Cholesky). On:
  // only the first of a Solve is; later ones are solved by conjugate
  // gradients preconditioned with the last factor, to a relative residual of
  // 1e-6, a fresh factor when that needs more than 8 iterations
  // (WindowLinearization::SolveDampedWithKeptFactor; docs/speed.md).
  bool kept_factor_pcg = false;
};

// One step's problem. Clear() keeps the vectors' capacity, so a solver used
// step after step stops allocating once it has seen the largest window.
struct WindowSolverProblem {
  std::vector<WindowSolverBlock> blocks;
  std::vector<WindowSolverResidual> residuals;
  std::vector<int> block_indices;  // every residual's blocks, packed

  void Clear() {
    blocks.clear();
    residuals.clear();
    block_indices.clear();
  }
};

class WindowLinearization;

// Keeps its buffers from one Solve to the next (one per estimator).
class WindowSolver {
 public:
  WindowSolver();
  ~WindowSolver();
  WindowSolver(WindowSolver&&) noexcept;
  WindowSolver& operator=(WindowSolver&&) noexcept;

  // The problem to fill before Solve, cleared.
  WindowSolverProblem* NewProblem() {
    problem_.Clear();
    return &problem_;
  }
  const WindowSolverProblem& problem() const { return problem_; }

  // Minimises problem(): see SolveWindow.
  ceres::Solver::Summary Solve(const WindowSolverOptions& options);

 private:
  WindowSolverProblem problem_;
  std::unique_ptr<WindowLinearization> linearization_;
};

// Minimises the problem, writing the solution into the blocks' values.
// Returns a ceres::Solver::Summary with the fields this solver has:
// termination_type (CONVERGENCE, NO_CONVERGENCE at the iteration or time
// limit, FAILURE when the residuals cannot be evaluated at the start),
// message, initial_cost, final_cost, iterations (iteration 0 and one entry
// per step, as Ceres reports them), and the times (wall clock):
// preprocessor (structure set-up), jacobian_evaluation (residuals with
// Jacobians), residual_evaluation (cost only), linear_solver (Schur
// complement, Cholesky and back substitution), total.
// Throws std::invalid_argument when the structure breaks a requirement above
// (a programming error, not a data error).
// (WindowSolver::Solve does the same with buffers kept between calls.)
ceres::Solver::Summary SolveWindow(const WindowSolverProblem& problem,
                                   const WindowSolverOptions& options);

}  // namespace vio

#endif  // VIO_ESTIMATOR_WINDOW_SOLVER_H_
