#include "estimator/null_space_floor.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
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

bool LargestEigenvalue(const Eigen::MatrixXd& H, double* lambda_max) {
  const int k = static_cast<int>(H.rows());
  if (k == 0) return false;
  const int steps = std::min(k, kLanczosSteps);
  // Lanczos: H Q_j = Q_j T_j + beta_j q_{j+1} e_j^T with T_j tridiagonal
  // (alpha on the diagonal, beta below); the largest eigenvalue theta of T_j
  // is a Rayleigh quotient of H (so at most the largest eigenvalue), and
  // |H x - theta x| = beta_j |y_j| for its Ritz vector x = Q_j y.
  Eigen::MatrixXd Q(k, steps);
  std::vector<double> alpha, beta;
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd q(k);
  for (int i = 0; i < k; ++i) q[i] = u(rng);
  q.normalize();
  Eigen::VectorXd w(k);
  for (int j = 0; j < steps; ++j) {
    Q.col(j) = q;
    w.noalias() = H * q;
    alpha.push_back(q.dot(w));
    // Full reorthogonalisation against every earlier q, twice (classical
    // Gram-Schmidt twice is orthogonal to rounding).
    for (int pass = 0; pass < 2; ++pass) {
      const Eigen::VectorXd c = Q.leftCols(j + 1).transpose() * w;
      w.noalias() -= Q.leftCols(j + 1) * c;
    }
    const double b = w.norm();
    const Eigen::Map<const Eigen::VectorXd> diagonal(alpha.data(), j + 1);
    const Eigen::Map<const Eigen::VectorXd> below(beta.data(), j);
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> ritz;
    ritz.computeFromTridiagonal(diagonal, below, Eigen::ComputeEigenvectors);
    if (ritz.info() != Eigen::Success) return false;
    const double theta = ritz.eigenvalues()[j];  // ascending
    const double bound = b * std::abs(ritz.eigenvectors()(j, j));
    // Converged, or the Krylov space is invariant (theta is exact).
    if (bound <= kLanczosTolerance * std::abs(theta) || j + 1 == k) {
      *lambda_max = theta;
      return std::isfinite(theta);
    }
    if (!(b > 0.0)) break;  // invariant but the bound was not met: refuse
    beta.push_back(b);
    q = w / b;
  }
  return false;
}

namespace {

// True when the symmetric block B - s I has a Cholesky factor (every
// eigenvalue of B above s); without allocating for the usual block sizes.
template <typename Block>
bool AllAbove(const Block& B, double s) {
  constexpr int kSmall = 9;  // a speed-bias block, the largest kept one
  if (B.rows() <= kSmall) {
    using Small = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0,
                                kSmall, kSmall>;
    Small shifted = B;
    shifted.diagonal().array() -= s;
    return Eigen::LLT<Small>(shifted).info() == Eigen::Success;
  }
  Eigen::MatrixXd shifted = B;
  shifted.diagonal().array() -= s;
  return Eigen::LLT<Eigen::MatrixXd>(shifted).info() == Eigen::Success;
}

}  // namespace

bool FloorBlockDirections(const Eigen::MatrixXd& H, double floor,
                          const std::vector<CoordinateBlock>& blocks,
                          Eigen::MatrixXd* H_floored, int* floored) {
  const int k = static_cast<int>(H.rows());
  int next = 0;
  for (const CoordinateBlock& b : blocks) {
    if (b.offset < next || b.size < 1 || b.offset + b.size > k) return false;
    next = b.offset + b.size;
  }
  double lambda_max = 0.0;
  if (!LargestEigenvalue(H, &lambda_max) || !(lambda_max > 0.0)) return false;
  const double s_min = floor * lambda_max;
  // The blocks' directions below s_min: H_f = H + (s_min - t) v v^T each.
  Eigen::MatrixXd H_f = H;
  int m = 0;
  for (const CoordinateBlock& b : blocks) {
    if (AllAbove(H.block(b.offset, b.offset, b.size, b.size), s_min)) {
      continue;  // every eigenvalue of H_bb above s_min
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(
        H.block(b.offset, b.offset, b.size, b.size));
    if (eig.info() != Eigen::Success) return false;
    for (int i = 0; i < b.size && eig.eigenvalues()[i] < s_min; ++i) {
      const Eigen::VectorXd u = eig.eigenvectors().col(i);
      const double t = eig.eigenvalues()[i];
      // (a): H v - t v, with v = u on the block (H's block columns times u).
      Eigen::VectorXd residual = H.middleCols(b.offset, b.size) * u;
      residual.segment(b.offset, b.size) -= t * u;
      if (!(residual.norm() <= kNullFraction * s_min)) return false;
      H_f.block(b.offset, b.offset, b.size, b.size) +=
          (s_min - t) * (u * u.transpose());
      ++m;
    }
  }
  if (m == 0) return false;
  *H_floored = std::move(H_f);
  *floored = m;
  return true;
}

}  // namespace vio
