#include "estimator/null_space_floor.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <random>
#include <vector>

namespace vio {

bool FloorNullSpace(const Eigen::MatrixXd& H, double floor,
                    Eigen::MatrixXd* H_floored, int* floored) {
  const int k = static_cast<int>(H.rows());
  if (k == 0) return false;
  // The eigenvalues only: s_min and m exactly as the eigen path sees them.
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> values(
      H, Eigen::EigenvaluesOnly);
  if (values.info() != Eigen::Success) return false;
  const Eigen::VectorXd& s = values.eigenvalues();  // ascending
  const double s_max = s[k - 1];
  if (!(s_max > 0.0)) return false;
  const double s_min = floor * s_max;
  int m = 0;
  while (m < k && s[m] < s_min) ++m;
  if (m == k || (m > 0 && !(s[m - 1] <= kNullFraction * s_min))) {
    return false;
  }

  if (m == 0) {  // nothing to floor: H_f is H
    *H_floored = H;
    *floored = 0;
    return true;
  }
  // N's basis by inverse subspace iteration: (H + sigma I)^-1 has the
  // eigenvalues 1 / (s_i + sigma), at least 1 / (2 sigma) on N and at most
  // 1 / (s_min + sigma) elsewhere, so each step shrinks the other
  // directions by 2 sigma / (s_min + sigma) < 0.02 (sigma = kNullFraction *
  // s_min); kSubspaceSteps steps from a seeded start reach rounding.
  const double sigma = kNullFraction * s_min;
  Eigen::MatrixXd shifted = H;
  shifted.diagonal().array() += sigma;
  const Eigen::LLT<Eigen::MatrixXd> llt(shifted);
  if (llt.info() != Eigen::Success) return false;
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::MatrixXd X(k, m);
  for (int i = 0; i < X.size(); ++i) X.data()[i] = u(rng);
  for (int step = 0; step < kSubspaceSteps; ++step) {
    llt.solveInPlace(X);
    X = Eigen::HouseholderQR<Eigen::MatrixXd>(X).householderQ() *
        Eigen::MatrixXd::Identity(k, m);
  }
  const Eigen::MatrixXd& Q = X;  // orthonormal
  const Eigen::MatrixXd HQ = H * Q;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> ritz(Q.transpose() * HQ);
  if (ritz.info() != Eigen::Success) return false;
  const Eigen::VectorXd& t = ritz.eigenvalues();
  const Eigen::MatrixXd W = Q * ritz.eigenvectors();
  const double residual =
      (HQ * ritz.eigenvectors() - W * t.asDiagonal()).norm();
  if (!(t.maxCoeff() <= kNullFraction * s_min) ||
      !(residual <= kNullFraction * s_min)) {
    return false;
  }
  const Eigen::VectorXd lift = (s_min - t.array()).matrix();
  *H_floored = H;
  H_floored->noalias() += W * lift.asDiagonal() * W.transpose();
  *H_floored = (0.5 * (*H_floored + H_floored->transpose())).eval();
  *floored = m;
  return true;
}

}  // namespace vio
