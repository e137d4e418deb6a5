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

}  // namespace vio

#endif  // VIO_ESTIMATOR_NULL_SPACE_FLOOR_H_
