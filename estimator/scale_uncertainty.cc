#include "estimator/scale_uncertainty.h"

#include <ceres/covariance.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <utility>

namespace vio {

double RelativeSpreadSigma(ceres::Problem* problem,
                           const std::vector<const double*>& poses) {
  const size_t n = poses.size();
  if (n < 2) return -1.0;
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const double* p : poses) c += Eigen::Vector3d(p);
  c /= static_cast<double>(n);
  double s2 = 0.0;
  for (const double* p : poses) s2 += (Eigen::Vector3d(p) - c).squaredNorm();
  const double spread = std::sqrt(s2 / static_cast<double>(n));
  if (!(spread > 0.0)) return -1.0;
  ceres::Covariance::Options options;
  options.num_threads = 1;
  if (!ceres::IsSparseLinearAlgebraLibraryTypeAvailable(ceres::SUITE_SPARSE)) {
    options.sparse_linear_algebra_library_type = ceres::EIGEN_SPARSE;
  }
  ceres::Covariance covariance(options);
  std::vector<std::pair<const double*, const double*>> pairs;
  for (size_t j = 0; j < n; ++j) {
    for (size_t k = j; k < n; ++k) pairs.emplace_back(poses[j], poses[k]);
  }
  if (!covariance.Compute(pairs, problem)) return -1.0;
  // g_k = (p_k - c) / (n S); the tangent's first three are the position.
  std::vector<Eigen::Vector3d> g(n);
  for (size_t k = 0; k < n; ++k) {
    g[k] = (Eigen::Vector3d(poses[k]) - c) / (static_cast<double>(n) * spread);
  }
  double var = 0.0;
  Eigen::Matrix<double, 6, 6, Eigen::RowMajor> block;
  for (size_t j = 0; j < n; ++j) {
    for (size_t k = j; k < n; ++k) {
      if (!covariance.GetCovarianceBlockInTangentSpace(poses[j], poses[k],
                                                       block.data())) {
        return -1.0;
      }
      const double term = g[j].dot(block.topLeftCorner<3, 3>() * g[k]);
      var += j == k ? term : 2.0 * term;  // Sigma_kj = Sigma_jk^T
    }
  }
  if (!std::isfinite(var)) return -1.0;
  return std::sqrt(std::max(0.0, var)) / spread;
}

}  // namespace vio
