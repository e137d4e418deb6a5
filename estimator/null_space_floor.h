#ifndef VIO_ESTIMATOR_NULL_SPACE_FLOOR_H_
#define VIO_ESTIMATOR_NULL_SPACE_FLOOR_H_

// The floored information of the marginalisation's square root
// (marginalization.h, step 4) without the eigenvectors of the whole matrix,
// for the case the world points (landmarks.reanchored_tracks keep_point*)
// bring: H* positive semi-definite whose eigenvalues below the floor are
// exact zeros (a point converted in this step with one folded sighting has
// no information along its ray: one zero per such point), all others at or
// above it.
//
// The eigen path computes, with H* = V S V^T and s_min = floor * max(S),
//   H_f = V max(S, s_min) V^T
// at about 10 k^3 flops for k x k (docs/speed.md has the profile: 15 of the
// 17 ms of a keep_point_fej marginalisation). H_f differs from H* only on
// the span N of the eigenvectors with S < s_min:
//   H_f = H* + sum_{i in N} (s_min - s_i) v_i v_i^T.
// Here: the eigenvalues alone (tridiagonalisation, no eigenvectors) give
// s_min and m = dim N; N's basis Q (k x m, orthonormal) comes from inverse
// subspace iteration with one Cholesky factor of H* + sigma I (sigma =
// kNullFraction * s_min), which shrinks every direction outside N by less
// than 0.02 per step; rotated to H*'s eigenvectors on that span
// (Rayleigh-Ritz: Q^T H* Q = U diag(t) U^T, W = Q U),
//   H_f = H* + W diag(s_min - t) W^T,
// which is the eigen path's H_f when W spans N (the residual check below
// bounds W's angle to N by about kNullFraction; exact zeros give residuals
// at rounding, and on sim_default the two paths' trajectories agree to
// 1.3 um). About 1.5 k^3 flops, most of it the tridiagonalisation.

#include <Eigen/Core>
#include <vector>

namespace vio {

// Writes H_f (symmetric) and the number m of floored eigenvalues and
// returns true when the case above holds: every eigenvalue of the symmetric
// H below s_min = floor * max eigenvalue is at most kNullFraction * s_min,
// and the m vectors found leave a residual |H W - W diag(t)| (Frobenius) of
// at most kNullFraction * s_min (W's angle to N at most about that). Returns
// false otherwise (nothing written): the caller takes the eigen path. Also
// false when the largest eigenvalue is not > 0. With nothing below s_min,
// H_f is H and m = 0.
bool FloorNullSpace(const Eigen::MatrixXd& H, double floor,
                    Eigen::MatrixXd* H_floored, int* floored);

// The bound above, a fraction of s_min.
constexpr double kNullFraction = 1e-2;
// Steps of the subspace iteration (each shrinks the rest by < 0.02).
constexpr int kSubspaceSteps = 6;

// The same floor when every floored eigenvector lies within one block of
// H's coordinates (the marginalisation's kept blocks). That is the world
// points' case: a point converted with one folded mono sighting holds
// nothing along that camera's ray, and that direction u on the point's
// block, zero elsewhere (v), is an exact null vector of H*: the sighting's
// Jacobian has J_p u = 0 (the projection does not change along the ray), so
// J v = 0 for the whole stacked Jacobian of the step (no other residual block
// touches the point), and v^T H* v = min over x_m of |J [x_m; v]|^2 <=
// |J [0; v]|^2 = 0 with H* positive semi-definite: H* v = 0, whatever the
// loss's scale or the extrinsic. A ray floored by an earlier step and
// untouched since stays an eigenvector (eigenvalue that step's s_min) and is
// floored again when the largest eigenvalue has grown. Then no eigenvalue
// pass over the whole matrix is needed:
//   s_min = floor * max eigenvalue, the largest eigenvalue by Lanczos
//           (LargestEigenvalue below, converged to kLanczosTolerance);
//   each block whose diagonal block H_bb - s_min I has no Cholesky factor
//   (an eigenvalue of H_bb below s_min: H* has one too, v^T H v = u^T H_bb u)
//   is eigen-decomposed: every u with H_bb u = t u, t < s_min, gives v;
//   H_f = H + sum_i (s_min - t_i) v_i v_i^T,
// which is the eigen path's H_f (to rounding) when
//   (a) each v_i is an eigenvector of H: |H v_i - t_i v_i| <= kNullFraction
//       * s_min (blocks do not overlap, so the v_i are orthonormal; else
//       refused);
//   (b) no other eigenvalue of H lies below s_min. That is not checked here
//       (a check by Sylvester's inertia costs a second Cholesky factor, as
//       much as the rest of the floor): the caller accepts H_f when its
//       Cholesky factor passes the test H* itself must pass to be used
//       unfloored (marginalization.cc: every pivot^2 at least the floor
//       times the largest), which an exact zero elsewhere fails. An
//       eigenvalue in (0, s_min) outside the blocks that passes it stays as
//       it is, as it would in H* on that path. (On sim_default and
//       sim_stereo the inertia check, tried, never refused: docs/speed.md.)
// About k^2 per Lanczos step and the blocks' small eigen solves, then the
// caller's Cholesky factor (k^3 / 3), against the eigenvalues' 4 k^3 / 3 and
// the eigen path's 10 k^3.
struct CoordinateBlock {
  int offset = 0;  // first coordinate in H
  int size = 0;
};

// Writes H_f and m (the number of floored directions, > 0) and returns true
// when (a) holds and Lanczos converged; false otherwise (nothing written):
// the caller takes another path. blocks: consecutive, non-overlapping,
// within H (else false). Also false when no block has an eigenvalue below
// s_min or the largest eigenvalue is not > 0.
bool FloorBlockDirections(const Eigen::MatrixXd& H, double floor,
                          const std::vector<CoordinateBlock>& blocks,
                          Eigen::MatrixXd* H_floored, int* floored);

// The largest eigenvalue of the symmetric H by Lanczos with full
// reorthogonalisation from a seeded start: true when the Ritz value's error
// bound |beta_j y_j| (Parlett) is at most kLanczosTolerance of it within
// kLanczosSteps steps (or the Krylov space is exhausted), false otherwise.
bool LargestEigenvalue(const Eigen::MatrixXd& H, double* lambda_max);
constexpr int kLanczosSteps = 60;
constexpr double kLanczosTolerance = 1e-12;

}  // namespace vio

#endif  // VIO_ESTIMATOR_NULL_SPACE_FLOOR_H_
