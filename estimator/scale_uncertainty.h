#ifndef VIO_ESTIMATOR_SCALE_UNCERTAINTY_H_
#define VIO_ESTIMATOR_SCALE_UNCERTAINTY_H_

// How well a window problem determines the metric scale of its trajectory:
// the relative standard deviation of the spread
//   S = sqrt(1/n sum_k |p_k - c|^2),   c = 1/n sum_k p_k,
// of its frames' positions, from the Gauss-Newton covariance of the
// positions (every other block marginalised, as estimator/pose_covariance.h
// computes a pose's). A monocular start's scale error is the error of S
// (test/benchmark/init_benchmark measures it so), and its linearised
// variance is
//   Var(S) = sum_jk g_j^T Sigma_jk g_k,   g_k = dS/dp_k = (p_k - c) / (n S)
// (the centroid's own derivative drops out: sum_k (p_k - c) = 0).

#include <ceres/problem.h>

#include <vector>

namespace vio {

// poses: blocks of `problem` (7 values [t, q], the project's PoseManifold),
// at least two at distinct positions. Returns sqrt(Var(S)) / S, or a
// negative value when Ceres cannot compute the covariance (a direction no
// residual constrains) or the positions coincide.
double RelativeSpreadSigma(ceres::Problem* problem,
                           const std::vector<const double*>& poses);

}  // namespace vio

#endif  // VIO_ESTIMATOR_SCALE_UNCERTAINTY_H_
