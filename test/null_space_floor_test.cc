#include "estimator/null_space_floor.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <random>

namespace vio {
namespace {

constexpr double kFloor = 1e-10;  // MarginalizationOptions' prior floor

// H = V diag(s) V^T with a seeded random orthogonal V.
Eigen::MatrixXd WithSpectrum(const Eigen::VectorXd& s, Eigen::MatrixXd* V) {
  std::mt19937 rng(42);
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::MatrixXd A(s.size(), s.size());
  for (int i = 0; i < A.size(); ++i) A.data()[i] = n(rng);
  *V = Eigen::HouseholderQR<Eigen::MatrixXd>(A).householderQ();
  Eigen::MatrixXd H = *V * s.asDiagonal() * V->transpose();
  return 0.5 * (H + H.transpose());
}

// The eigen path of marginalization.cc: V max(S, floor * max S) V^T.
Eigen::MatrixXd EigenPathFloor(const Eigen::MatrixXd& H, int* floored) {
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(H);
  Eigen::VectorXd s = eig.eigenvalues();
  const double s_min = kFloor * s.maxCoeff();
  *floored = 0;
  for (int i = 0; i < s.size(); ++i) {
    if (s[i] < s_min) {
      s[i] = s_min;
      ++*floored;
    }
  }
  return eig.eigenvectors() * s.asDiagonal() * eig.eigenvectors().transpose();
}

// A spectrum like a keep_point_fej prior's (docs/speed.md): a spread of
// eigenvalues over ten decades, a cluster just above the floor, and `zeros`
// exact zeros (converted points' rays).
Eigen::VectorXd PriorLikeSpectrum(int k, int zeros) {
  Eigen::VectorXd s(k);
  for (int i = 0; i < k; ++i) {
    s[i] = std::pow(10.0, 8.0 - 10.0 * i / (k - 1));  // 1e8 .. 1e-2
  }
  for (int i = 0; i < 6; ++i) s[k - 1 - zeros - i] = (1.5 + i) * 1e-2;
  for (int i = 0; i < zeros; ++i) s[k - 1 - i] = 0.0;
  return s;
}

TEST(NullSpaceFloor, EqualsTheEigenPathOnExactZeros) {
  Eigen::MatrixXd V;
  const Eigen::VectorXd s = PriorLikeSpectrum(90, 7);
  const Eigen::MatrixXd H = WithSpectrum(s, &V);
  Eigen::MatrixXd H_f;
  int floored = 0;
  ASSERT_TRUE(FloorNullSpace(H, kFloor, &H_f, &floored));
  int eigen_floored = 0;
  const Eigen::MatrixXd expected = EigenPathFloor(H, &eigen_floored);
  EXPECT_EQ(floored, 7);
  EXPECT_EQ(eigen_floored, 7);
  const double s_min = kFloor * s.maxCoeff();
  // Both to rounding of the largest eigenvalue, and along each true null
  // vector both give s_min (to the eigen path's own accuracy there).
  EXPECT_LT((H_f - expected).cwiseAbs().maxCoeff(), 1e-13 * s.maxCoeff());
  for (int i = 83; i < 90; ++i) {
    const Eigen::VectorXd v = V.col(i);
    EXPECT_NEAR(v.dot(H_f * v), s_min, 1e-3 * s_min) << i;
    EXPECT_NEAR(v.dot(expected * v), s_min, 1e-3 * s_min) << i;
  }
  // Elsewhere nothing changed: on the other eigenvectors H_f is H.
  for (int i = 0; i < 83; i += 5) {
    const Eigen::VectorXd v = V.col(i);
    EXPECT_NEAR(v.dot(H_f * v), s[i], 1e-13 * s.maxCoeff() + 1e-9 * s[i]);
  }
  EXPECT_EQ((H_f - H_f.transpose()).cwiseAbs().maxCoeff(), 0.0);
}

TEST(NullSpaceFloor, RefusesAnEigenvalueBetweenZeroAndTheFloor) {
  Eigen::MatrixXd V;
  Eigen::VectorXd s = PriorLikeSpectrum(60, 3);
  s[56] = 0.5 * kFloor * s.maxCoeff();  // floored, but no exact zero
  const Eigen::MatrixXd H = WithSpectrum(s, &V);
  Eigen::MatrixXd H_f;
  int floored = 0;
  EXPECT_FALSE(FloorNullSpace(H, kFloor, &H_f, &floored));
}

TEST(NullSpaceFloor, LeavesAMatrixWithNothingBelowTheFloorAsItIs) {
  Eigen::MatrixXd V;
  const Eigen::MatrixXd H = WithSpectrum(PriorLikeSpectrum(40, 0), &V);
  Eigen::MatrixXd H_f;
  int floored = -1;
  ASSERT_TRUE(FloorNullSpace(H, kFloor, &H_f, &floored));
  EXPECT_EQ(floored, 0);
  EXPECT_EQ((H_f - H).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_FALSE(
      FloorNullSpace(Eigen::MatrixXd::Zero(5, 5), kFloor, &H_f, &floored));
}

}  // namespace
}  // namespace vio
