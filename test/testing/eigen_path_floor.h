#ifndef VIO_TEST_TESTING_EIGEN_PATH_FLOOR_H_
#define VIO_TEST_TESTING_EIGEN_PATH_FLOOR_H_

// The reference for the prior's floored information: the eigen path of
// estimator/marginalization.cc, V max(S, floor * max S) V^T, from a full
// eigendecomposition. *floored receives how many eigenvalues were raised.

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

namespace vio::testing {

inline Eigen::MatrixXd EigenPathFloor(const Eigen::MatrixXd& H, double floor,
                                      int* floored) {
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(H);
  Eigen::VectorXd s = eig.eigenvalues();
  const double s_min = floor * s.maxCoeff();
  *floored = 0;
  for (int i = 0; i < s.size(); ++i) {
    if (s[i] < s_min) {
      s[i] = s_min;
      ++*floored;
    }
  }
  return eig.eigenvectors() * s.asDiagonal() * eig.eigenvectors().transpose();
}

}  // namespace vio::testing

#endif  // VIO_TEST_TESTING_EIGEN_PATH_FLOOR_H_
