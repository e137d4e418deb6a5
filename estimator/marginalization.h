#ifndef VIO_ESTIMATOR_MARGINALIZATION_H_
#define VIO_ESTIMATOR_MARGINALIZATION_H_

// Marginalisation: removes parameter blocks from the window and leaves their
// information on the remaining blocks as a MarginalizationPrior.
//
// Given the residual blocks that touch the leaving states, evaluated at the
// current values (which become the prior's linearisation point x0):
//   1. each block's tangent Jacobian J_i = J_ambient * PlusJacobian(x) and
//      residual r_i, scaled by sqrt(rho'(|r_i|^2)) when it has a robust loss
//      (first order only, see marginalization.cc for why no Triggs term);
//   2. the tangent-space system H = sum J_i^T J_i, b = -sum J_i^T r_i,
//      ordered [marginalised m | kept k] (estimator/marginalization_system.h);
//   3. the Schur complement
//        H* = H_kk - H_km H_mm^+ H_mk,   b* = b_k - H_km H_mm^+ b_m,
//      taken in two stages that give the same result: the marginalised
//      scalars (inverse depths: size 1, no residual block shared by two)
//      first, each a rank-one update (one with h_s not above a relative
//      floor carries no information and is dropped), then the remaining
//      marginalised blocks through the eigen-decomposition pseudo-inverse
//      H_mm^+ (eigenvalues below a relative floor are dropped);
//   4. H* symmetrised and a square root J with J^T J = H*, r0 with
//      J^T r0 = -b*: by Cholesky, H* = L L^T, J = L^T, r0 = -L^-1 b*, when
//      H* is positive definite and no pivot is below the floor times the
//      largest; otherwise by H* = V S V^T, S floored at a relative epsilon,
//        J = sqrt(S) V^T,   r0 = -sqrt(S)^-1 V^T b*.
//      When the floored eigenvalues are exact zeros (world points: one per
//      point converted with a single sighting) V max(S, eps) V^T is found
//      without the eigenvectors (null_space_floor.h: block by block when
//      each floored eigenvector lies in one kept block, else by inverse
//      subspace iteration) and J is its Cholesky factor: the same prior to
//      rounding.
//      Either way the prior r = r0 + J (x (-) x0) has the Schur complement's
//      Hessian and gradient at x0.
// References: Sibley et al., JFR 2010; Leutenegger et al., IJRR 2015 (the
// same construction; the prior stores a square root of H*).
//
// A previous prior is re-marginalised like any other residual block (see
// PriorResidualBlock below).

#include <ceres/cost_function.h>
#include <ceres/loss_function.h>
#include <ceres/manifold.h>

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "factors/marginalization_prior.h"

namespace vio {

// A parameter block as the marginalisation sees it.
struct MarginalizationParameterBlock {
  double* values = nullptr;  // current values, ambient layout (not owned)
  int size = 0;              // ambient size
  // nullptr: Euclidean. A kept block needs nullptr or a PoseManifold (the two
  // kinds a prior can hold); a marginalised block may have any manifold.
  const ceres::Manifold* manifold = nullptr;
  bool constant = false;  // held fixed in the problem: no columns, not kept

  int TangentSize() const { return manifold ? manifold->TangentSize() : size; }
};

// A residual block: what ceres::Problem::AddResidualBlock was given.
struct MarginalizationResidualBlock {
  const ceres::CostFunction* cost = nullptr;  // not owned
  const ceres::LossFunction* loss = nullptr;  // nullptr: squared loss
  std::vector<double*> parameter_blocks;      // in the cost's order
};

// Everything one marginalisation step needs.
struct MarginalizationProblem {
  // Every block any residual block touches (the marginalised ones included).
  std::vector<MarginalizationParameterBlock> parameter_blocks;
  // Every residual block that touches a marginalised block (and only those:
  // the others stay in the window as they are).
  std::vector<MarginalizationResidualBlock> residual_blocks;
  std::vector<const double*> marginalized;  // the blocks that leave
};

struct MarginalizationOptions {
  // Eigenvalues of H_mm below this fraction of its largest are treated as
  // directions without information (pseudo-inverse), [-].
  double marginalized_eigenvalue_floor = 1e-12;
  // Eigenvalues of H* are floored at this fraction of its largest, so that
  // sqrt(S)^-1 is finite; [-]. The added information, 1e-10 of the largest,
  // is far below anything a measurement carries. The Cholesky path is taken
  // only when every pivot of H* is at least this fraction of the largest.
  double prior_eigenvalue_floor = 1e-10;

  // True when both floors are finite and in [0, 1); else false + message.
  bool Validate(std::string* message) const;
};

// Which way step 4 took the square root of H*.
enum class PriorSquareRoot {
  kCholesky,        // H* positive definite: J = L^T, no floor
  kBlockFloor,      // floored eigenvectors each within one kept block
  kNullSpaceFloor,  // floored eigenvalues exact zeros (subspace iteration)
  kEigen,           // the eigen-decomposition of H*
};

enum class MarginalizationStatus {
  kOk,          // prior built from every residual block; H_mm full rank
  kDegenerate,  // prior built, but residual blocks were skipped or H_mm was
                // rank deficient: see the counters
  kFailed,      // no prior: invalid input or no information left (message)
};

// The outcome of one step, ready to become a MarginalizationPrior.
struct MarginalizationResult {
  MarginalizationStatus status = MarginalizationStatus::kFailed;
  std::string message;  // why it failed or what was degenerate

  int num_residual_blocks_used = 0;
  // Residual blocks whose Evaluate failed or returned a non-finite value, or
  // whose loss gave a non-finite or negative rho'; left out of the prior.
  int num_skipped_residual_blocks = 0;
  int marginalized_rank_deficiency = 0;  // dropped directions of H_mm
  // Eigenvalues of H* raised to the floor; 0 on the Cholesky path.
  int num_floored_eigenvalues = 0;
  PriorSquareRoot square_root = PriorSquareRoot::kCholesky;

  // The kept blocks, in the prior's parameter order, and their description
  // (kind and x0 = the values at marginalisation time).
  std::vector<double*> kept_parameter_blocks;
  std::vector<PriorBlock> kept_blocks;

  Eigen::MatrixXd information;  // H* (symmetric, before the floor)
  Eigen::VectorXd gradient;     // -b*: the cost's gradient on the kept blocks
  Eigen::MatrixXd jacobian;     // J = L^T, or sqrt(S) V^T (step 4)
  // With floored eigenvalues, J^T J when it is known without forming it (the
  // floor of null_space_floor.h); empty otherwise.
  Eigen::MatrixXd floored_information;
  Eigen::VectorXd residual0;  // r0 = -J^-T b*

  bool ok() const { return status != MarginalizationStatus::kFailed; }

  // The prior for the next window (Ceres takes ownership when it is added
  // with kept_parameter_blocks). Requires ok(). The second moves J, r0 and
  // the information into it (k x k each, 0.3 MB with world points) and
  // leaves them empty here.
  std::unique_ptr<MarginalizationPrior> MakePrior() const&;
  std::unique_ptr<MarginalizationPrior> MakePrior() &&;
};

// Runs one marginalisation step. Never throws on bad values and never returns
// a non-finite J or r0: problems are reported through status and the
// counters. A kept block is one that is listed, touched by a residual block,
// not constant and not marginalised.
MarginalizationResult Marginalize(const MarginalizationProblem& problem,
                                  const MarginalizationOptions& options = {});

// The residual block of a prior made from result, for re-marginalising it
// (prior must outlive the next step). Its blocks' manifolds: a PoseManifold
// for pose blocks, nullptr otherwise; the caller lists them as parameter
// blocks too (KeptParameterBlocks below).
MarginalizationResidualBlock PriorResidualBlock(
    const MarginalizationResult& result, const MarginalizationPrior* prior);

// The parameter-block descriptions of result's kept blocks, with manifold for
// the pose blocks.
std::vector<MarginalizationParameterBlock> KeptParameterBlocks(
    const MarginalizationResult& result, const ceres::Manifold* pose_manifold);

}  // namespace vio

#endif  // VIO_ESTIMATOR_MARGINALIZATION_H_
