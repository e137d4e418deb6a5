#include "estimator/pose_covariance.h"

#include <ceres/covariance.h>

#include <utility>
#include <vector>

namespace vio {

bool PoseCovariance(ceres::Problem* problem, const double* pose,
                    Eigen::Matrix<double, 6, 6>* covariance) {
  ceres::Covariance::Options options;
  options.num_threads = 1;
  // Sparse QR needs SuiteSparse; Eigen's sparse QR is always there.
  if (!ceres::IsSparseLinearAlgebraLibraryTypeAvailable(ceres::SUITE_SPARSE)) {
    options.sparse_linear_algebra_library_type = ceres::EIGEN_SPARSE;
  }
  ceres::Covariance covariance_computer(options);
  const std::vector<std::pair<const double*, const double*>> blocks = {
      {pose, pose}};
  if (!covariance_computer.Compute(blocks, problem)) return false;
  // Row-major 6x6 in the manifold's tangent space.
  Eigen::Matrix<double, 6, 6, Eigen::RowMajor> c;
  if (!covariance_computer.GetCovarianceBlockInTangentSpace(pose, pose,
                                                            c.data())) {
    return false;
  }
  *covariance = c;
  return covariance->allFinite();
}

}  // namespace vio
