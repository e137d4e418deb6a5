#ifndef VIO_ESTIMATOR_WINDOW_LINEARIZATION_H_
#define VIO_ESTIMATOR_WINDOW_LINEARIZATION_H_

// The linear algebra of one window step for estimator/window_solver.h: the
// residuals and tangent Jacobians at the current values, the normal
// equations with the inverse depths eliminated by their (scalar) Schur
// complements, and the damped solve. The iteration itself (trust region,
// stopping) is in window_solver.cc. The class is defined in three files:
// window_linearization.cc (the set-up of the structure, the state),
// window_linearization_residuals.cc (residuals and tangent Jacobians, the
// robust correction, the prior's linearisation, a candidate's cost) and
// window_linearization_schur.cc (the normal equations, the landmarks' Schur
// elimination, the damped solve).
//
// Notation (tangent space): r the stacked, robust-corrected residuals, J their
// Jacobian, A = J^T J and g = J^T r, split into reduced coordinates (index r)
// and eliminated ones (one per landmark l):
//   A = [A_rr  W  ]   g = [g_r]
//       [W^T   H_l]       [g_l],   H_l = diag(h_l), W's column l = w_l.
// A damped step solves (A + lambda D) dx = -g with D diagonal:
//   S  = A_rr + lambda D_r - sum_l w_l w_l^T / (h_l + lambda D_l)
//   S dx_r = -(g_r - sum_l w_l g_l / (h_l + lambda D_l))
//   dx_l = -(g_l + w_l^T dx_r) / (h_l + lambda D_l)
// which is the block elimination of the landmarks (exact, not approximate).
// A landmark without information (h_l = 0: every residual inactive) is left
// where it is (dx_l = 0).

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/IterativeLinearSolvers>
#include <vector>

#include "estimator/window_solver.h"

namespace vio {

class WindowLinearization {
 public:
  // Sets up the structure of problem (which must outlive the following
  // calls), re-using the buffers of the previous problem. Throws
  // std::invalid_argument when an eliminated block breaks the requirements
  // of WindowSolverBlock, a residual names a block that does not exist, or
  // its sizes disagree with its cost function.
  void SetUp(const WindowSolverProblem& problem);

  // Residuals, Jacobians and A, g at the blocks' current values; cost() is
  // then 1/2 sum rho(|r|^2). False when a residual cannot be evaluated or is
  // not finite (nothing else is then valid).
  bool Linearize();
  double cost() const { return cost_; }

  // The cost at values blocks' values (+) dx (projected onto the bounds),
  // without Jacobians; the candidate is kept for Accept(). False when a
  // residual cannot be evaluated or is not finite.
  bool CandidateCost(const Eigen::VectorXd& dx, double* cost);
  // Copies the last candidate into the blocks' values.
  void Accept();

  // Solves (A + lambda D) dx = -g as in the header comment, with D_i =
  // diag(A)_i clamped to [1e-6, 1e32]. False when the reduced system is not
  // positive definite. The Cholesky factor of S is kept for
  // SolveDampedWithKeptFactor until the next SetUp.
  bool SolveDamped(double lambda, Eigen::VectorXd* dx);

  // The same system solved without a new factor when possible: conjugate
  // gradients on S dx_r = rhs (S and rhs as in the header comment),
  // preconditioned by the Cholesky factor kept from an earlier S of this
  // problem (an earlier linearisation or damping), stopped at |S dx_r - rhs|
  // <= kPcgTolerance |rhs| (Euclidean norms). Without a kept factor, or when
  // the iteration has not converged after kMaxPcgIterations (the kept factor
  // too far from S), S is factored afresh exactly as in SolveDamped (that
  // factor is then kept). The inverse depths follow by the same back
  // substitution. A converged iteration does not test S for positive
  // definiteness (the kept factor's S passed it; a step moves S little).
  bool SolveDampedWithKeptFactor(double lambda, Eigen::VectorXd* dx);
  // Chosen on sim_default seed 1 (docs/speed.md): 1e-6 moves its
  // trajectory by 1.5 um (ATE 3.4 cm) and needs 4.4 iterations on average;
  // 8 iterations leave 1.4 % of the solves to a fresh factor.
  static constexpr double kPcgTolerance = 1e-6;
  static constexpr int kMaxPcgIterations = 8;

  // How the reduced systems since SetUp were solved.
  struct SolveCounts {
    int factorizations = 0;  // Cholesky factors computed (successful or not)
    int pcg_solves = 0;      // solved by conjugate gradients, converged
    int pcg_fallbacks = 0;   // conjugate gradients not converged: factored
    int pcg_iterations = 0;  // over all conjugate gradient runs
  };
  const SolveCounts& solve_counts() const { return solve_counts_; }

  // The gradient g (all tangent coordinates) and diag(A).
  const Eigen::VectorXd& gradient() const { return g_; }
  const Eigen::VectorXd& jtj_diagonal() const { return diagonal_; }
  // v^T A v = |J v|^2 for a tangent vector v, from A's blocks (no pass over
  // the residuals).
  double QuadraticForm(const Eigen::VectorXd& v) const;
  // max_i |x_i - Project(x_i - g_i)|: the gradient, with coordinates held at
  // a bound by a gradient pointing outwards counted as zero.
  double ProjectedGradientMaxNorm() const;
  // |x| over the ambient values of the blocks that are not constant.
  double StateNorm() const;

  int num_tangent() const { return num_tangent_; }

 private:
  enum class Role { kConstant, kReduced, kEliminated };
  struct Block {
    Role role = Role::kConstant;
    int tangent = 0;
    int offset = -1;  // into the tangent vector (reduced first, then landmarks)
    int plus_offset = -1;  // into plus_ (manifold blocks)
    int state_offset = 0;  // into candidate_ (ambient)
  };
  struct Term {  // one parameter block of one residual
    int block = 0;
    int jacobian_offset =
        -1;             // into jacobians_ (tangent, row-major); -1: constant
    int w_offset = -1;  // reduced blocks of a landmark's residual: into w_
  };
  struct Residual {
    int prior = -1;  // index into priors_ when it is a prior
    int rows = 0;
    int residual_offset = 0;  // into r_
    int first_term = 0;       // into terms_
    int num_terms = 0;
    int landmark = -1;       // the eliminated block's landmark index
    int landmark_term = -1;  // index into terms_
  };
  // A marginalisation prior's normal equations in its own tangent order.
  struct Prior {
    const MarginalizationPrior* factor = nullptr;
    std::vector<int> blocks;      // solver block of each prior block
    Eigen::MatrixXd information;  // M^T (J^T J) M
    Eigen::VectorXd gradient;     // M^T (J^T r0 + J^T J dx)
    Eigen::VectorXd delta;        // scratch: x (-) x0
  };
  struct Landmark {
    int block = 0;
    std::vector<int> touched;  // reduced blocks whose w part it has
    int w_offset = 0;          // into w_
    int w_size = 0;
  };

  void SetUpBlocks();
  void SetUpResiduals();
  void SetUpPrior(int k, Residual* res);
  void SetUpLandmarkParts();
  // The prior's normal equations at the current values (Prior above).
  bool LinearizePrior(int k);
  // Residual k and its tangent Jacobians, uncorrected; false when it cannot
  // be evaluated or is not finite.
  bool EvaluateResidual(int k);
  // Applies residual k's robust loss to its residual and Jacobians and adds
  // its cost.
  void Correct(int k, double* cost);
  void BuildNormalEquations();
  void AddSchurOfLandmark(const Landmark& l, double inv_h,
                          Eigen::MatrixXd* S) const;
  // S_, rhs_ and inv_h_ of the damped system (header comment).
  void FormReducedSystem(double lambda);
  // llt_ = Cholesky(S_); false when S_ is not positive definite.
  bool Factor();
  // dx_l from dx_r (header comment); true when dx is finite.
  bool BackSubstitute(Eigen::VectorXd* dx) const;

  // Applies the kept Cholesky factor's inverse as the preconditioner of
  // Eigen's ConjugateGradient (the interface Eigen asks of one).
  class KeptFactor {
   public:
    KeptFactor() = default;
    template <typename M>
    explicit KeptFactor(const M&) {}
    template <typename M>
    KeptFactor& analyzePattern(const M&) {
      return *this;
    }
    template <typename M>
    KeptFactor& factorize(const M&) {
      return *this;
    }
    template <typename M>
    KeptFactor& compute(const M&) {
      return *this;
    }
    template <typename Rhs>
    Eigen::VectorXd solve(const Rhs& b) const {
      return llt->solve(b);
    }
    Eigen::ComputationInfo info() const { return Eigen::Success; }
    const Eigen::LLT<Eigen::MatrixXd, Eigen::Upper>* llt = nullptr;
  };

  const std::vector<WindowSolverBlock>* blocks_in_ = nullptr;
  const std::vector<WindowSolverResidual>* residuals_in_ = nullptr;
  const std::vector<int>* block_indices_ = nullptr;
  std::vector<Block> blocks_;
  std::vector<Term> terms_;
  std::vector<Residual> residuals_;
  std::vector<Landmark> landmarks_;
  std::vector<Prior> priors_;
  std::vector<const double*> parameters_;  // per term: current values
  std::vector<const double*> candidates_;  // per term: candidate values
  int num_reduced_ = 0;
  int num_tangent_ = 0;
  int max_ambient_jacobian_ = 0;

  std::vector<double> plus_;           // PlusJacobian of manifold blocks
  std::vector<double> r_;              // corrected residuals
  std::vector<double> jacobians_;      // corrected tangent Jacobians
  std::vector<double> ambient_;        // scratch for Evaluate's Jacobians
  std::vector<double*> ambient_ptrs_;  // scratch
  std::vector<double> candidate_;      // ambient candidate values
  std::vector<double> scratch_r_;      // residuals of a candidate
  double cost_ = 0.0;

  Eigen::MatrixXd A_rr_;      // upper triangle valid
  Eigen::VectorXd g_;         // [g_r; g_l]
  Eigen::VectorXd diagonal_;  // diag(A), all coordinates
  std::vector<double> w_;     // every landmark's w, packed
  Eigen::MatrixXd S_;         // damped Schur complement (upper)
  Eigen::LLT<Eigen::MatrixXd, Eigen::Upper> llt_;
  bool factor_kept_ = false;  // llt_ factors an earlier S of this problem
  Eigen::ConjugateGradient<Eigen::MatrixXd, Eigen::Upper, KeptFactor> pcg_;
  SolveCounts solve_counts_;
  Eigen::VectorXd rhs_;        // scratch of SolveDamped
  std::vector<double> inv_h_;  // scratch of SolveDamped
};

}  // namespace vio

#endif  // VIO_ESTIMATOR_WINDOW_LINEARIZATION_H_
