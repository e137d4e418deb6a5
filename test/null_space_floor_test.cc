#include "estimator/null_space_floor.h"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <algorithm>
#include <random>
#include <vector>

#include "test/testing/eigen_path_floor.h"

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
  const Eigen::MatrixXd expected =
      testing::EigenPathFloor(H, kFloor, &eigen_floored);
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

// H with unit vectors v_i, each on one block of `at`, as eigenvectors of
// eigenvalue t_i (and, with `across` set, one more unit vector spanning all
// coordinates, orthogonal to them, with eigenvalue *across), and the
// eigenvalues `rest` on a seeded random orthonormal basis of their
// complement: H = V diag(t) V^T + Q diag(rest) Q^T, [V Q] orthogonal.
Eigen::MatrixXd WithBlockEigenvectors(const Eigen::VectorXd& rest,
                                      const std::vector<CoordinateBlock>& at,
                                      const Eigen::VectorXd& t,
                                      Eigen::MatrixXd* V,
                                      const double* across = nullptr) {
  const int m = static_cast<int>(at.size()) + (across ? 1 : 0);
  const int k = static_cast<int>(rest.size()) + m;
  std::mt19937 rng(7);
  std::normal_distribution<double> n(0.0, 1.0);
  V->setZero(k, m);
  Eigen::VectorXd values(m);
  for (size_t i = 0; i < at.size(); ++i) {
    Eigen::VectorXd u(at[i].size);
    for (int j = 0; j < u.size(); ++j) u[j] = n(rng);
    V->col(i).segment(at[i].offset, at[i].size) = u.normalized();
    values[i] = t[i];
  }
  Eigen::MatrixXd A(k, k);
  for (int i = 0; i < A.size(); ++i) A.data()[i] = n(rng);
  if (across) {
    const int b = m - 1;
    Eigen::VectorXd y = A.col(0);
    y -= V->leftCols(b) * (V->leftCols(b).transpose() * y);
    V->col(b) = y.normalized();
    values[b] = *across;
  }
  // Q: the last k - m columns of an orthogonal basis whose first m columns
  // span V's columns.
  A.leftCols(m) = *V;
  const Eigen::MatrixXd basis =
      Eigen::HouseholderQR<Eigen::MatrixXd>(A).householderQ();
  const Eigen::MatrixXd Q = basis.rightCols(k - m);
  Eigen::MatrixXd H = *V * values.asDiagonal() * V->transpose() +
                      Q * rest.asDiagonal() * Q.transpose();
  return 0.5 * (H + H.transpose());
}

// Blocks of a prior's layout: 3-wide points, then 6-wide poses.
std::vector<CoordinateBlock> PriorBlocks(int points, int poses) {
  std::vector<CoordinateBlock> blocks;
  int offset = 0;
  for (int i = 0; i < points + poses; ++i) {
    const int size = i < points ? 3 : 6;
    blocks.push_back({offset, size});
    offset += size;
  }
  return blocks;
}

// A spectrum with nothing below 1.5e-2 (1.5 times the floor of its largest
// eigenvalue, 1e8): the directions of WithBlockEigenvectors are then the only
// ones the floor raises.
Eigen::VectorXd AboveTheFloor(int k) {
  Eigen::VectorXd s = PriorLikeSpectrum(k, 0);
  for (int i = 0; i < k; ++i) s[i] = std::max(s[i], 1.5e-2);
  return s;
}

TEST(LargestEigenvalue, EqualsTheEigenSolversOnAPriorLikeSpectrum) {
  Eigen::MatrixXd V;
  for (const int zeros : {0, 7}) {
    const Eigen::MatrixXd H = WithSpectrum(PriorLikeSpectrum(120, zeros), &V);
    const double expected = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(
                                H, Eigen::EigenvaluesOnly)
                                .eigenvalues()
                                .maxCoeff();
    double lambda_max = 0.0;
    ASSERT_TRUE(LargestEigenvalue(H, &lambda_max));
    EXPECT_NEAR(lambda_max, expected, 1e-12 * expected) << zeros;
  }
}

// Six points with one exact zero each (a ray) and one with an eigenvalue at
// half the floor (a ray floored by an earlier step, the largest eigenvalue
// grown since): H_f equals the eigen path's.
TEST(FloorBlockDirections, EqualsTheEigenPathOnBlockEigenvectors) {
  const std::vector<CoordinateBlock> blocks = PriorBlocks(20, 10);
  const std::vector<CoordinateBlock> at = {blocks[0], blocks[3],  blocks[4],
                                           blocks[9], blocks[15], blocks[19],
                                           blocks[12]};
  const Eigen::VectorXd prior_like = AboveTheFloor(113);  // k = 120
  const double s_min = kFloor * prior_like.maxCoeff();
  Eigen::VectorXd t = Eigen::VectorXd::Zero(7);
  t[6] = 0.5 * s_min;
  Eigen::MatrixXd V;
  const Eigen::MatrixXd H = WithBlockEigenvectors(prior_like, at, t, &V);
  Eigen::MatrixXd H_f;
  int floored = 0;
  ASSERT_TRUE(FloorBlockDirections(H, kFloor, blocks, &H_f, &floored));
  int eigen_floored = 0;
  const Eigen::MatrixXd expected =
      testing::EigenPathFloor(H, kFloor, &eigen_floored);
  EXPECT_EQ(floored, 7);
  EXPECT_EQ(eigen_floored, 7);
  EXPECT_LT((H_f - expected).cwiseAbs().maxCoeff(),
            1e-13 * prior_like.maxCoeff());
  for (int i = 0; i < 7; ++i) {
    EXPECT_NEAR(V.col(i).dot(H_f * V.col(i)), s_min, 1e-3 * s_min) << i;
  }
  EXPECT_EQ((H_f - H_f.transpose()).cwiseAbs().maxCoeff(), 0.0);
}

// Nothing to floor in a block, or a block's small direction that is not an
// eigenvector of H: refused, the caller takes another path. Another
// eigenvalue below the floor, its eigenvector across blocks, is not floored
// here (the caller's Cholesky test decides, null_space_floor.h (b)): an
// exact zero leaves H_f singular.
TEST(FloorBlockDirections, RefusesWhatItCannotFloor) {
  const std::vector<CoordinateBlock> blocks = PriorBlocks(10, 5);
  const std::vector<CoordinateBlock> at = {blocks[1], blocks[4]};
  const Eigen::VectorXd prior_like = AboveTheFloor(58);  // k = 60
  const double s_min = kFloor * prior_like.maxCoeff();
  Eigen::MatrixXd V, H_f;
  int floored = 0;
  // The blocks' two zeros alone: accepted (the reference case).
  const Eigen::MatrixXd H =
      WithBlockEigenvectors(prior_like, at, Eigen::VectorXd::Zero(2), &V);
  ASSERT_TRUE(FloorBlockDirections(H, kFloor, blocks, &H_f, &floored));
  EXPECT_EQ(floored, 2);
  // Nothing in a block below the floor: nothing to floor block by block.
  Eigen::MatrixXd unused;
  EXPECT_FALSE(FloorBlockDirections(WithSpectrum(AboveTheFloor(60), &unused),
                                    kFloor, blocks, &H_f, &floored));
  for (const double extra : {0.0, 0.5 * s_min}) {
    // One more eigenvalue below the floor, its eigenvector y across blocks:
    // the blocks' two are floored, y keeps its eigenvalue.
    Eigen::MatrixXd V_extra;
    const Eigen::MatrixXd H_extra = WithBlockEigenvectors(
        prior_like.head(57), at, Eigen::VectorXd::Zero(2), &V_extra, &extra);
    ASSERT_TRUE(FloorBlockDirections(H_extra, kFloor, blocks, &H_f, &floored));
    EXPECT_EQ(floored, 2);
    const Eigen::VectorXd y = V_extra.col(2);
    EXPECT_NEAR(y.dot(H_f * y), extra, 1e-6 * s_min);
    if (extra == 0.0) {
      const Eigen::LLT<Eigen::MatrixXd> llt(H_f);
      const Eigen::VectorXd pivots = llt.matrixLLT().diagonal().cwiseAbs2();
      EXPECT_TRUE(llt.info() != Eigen::Success ||
                  pivots.minCoeff() < kFloor * pivots.maxCoeff());
    }
  }
  // A block's direction below the floor coupled to the rest: v^T H v is
  // small but H v is not t v.
  Eigen::MatrixXd coupled = H;
  const Eigen::VectorXd w = Eigen::VectorXd::Unit(60, 59);  // another block
  coupled +=
      0.1 * s_min * (V.col(0) * w.transpose() + w * V.col(0).transpose());
  EXPECT_FALSE(FloorBlockDirections(coupled, kFloor, blocks, &H_f, &floored));
  // Overlapping blocks are refused.
  EXPECT_FALSE(
      FloorBlockDirections(H, kFloor, {{0, 3}, {2, 3}}, &H_f, &floored));
}

}  // namespace
}  // namespace vio
