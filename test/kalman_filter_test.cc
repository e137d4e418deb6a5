// The notes' linear Kalman filter (Algorithm 2) against independent results:
// the notes' R_t entry by entry, the closed-form alpha-beta steady-state
// gains, the notes' (E - K)Sigma_bar covariance, and chi-square consistency
// (NEES, NIS) over Monte-Carlo runs of the model itself.

#include "navigation/kalman_filter.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <random>

#include "navigation/white_acceleration_model.h"
#include "testing/chi_square.h"

namespace vio {
namespace {

using testing::ChiSquareQuantile;
using testing::kZ975;

// The notes' R_t for the planar state (X, Xdot, Z, Zdot, theta, thetadot),
// typed from the notes entry by entry. `last_k` is the k of the last entry:
// the notes write k2 there, the model needs k3.
Eigen::MatrixXd NotesProcessNoise(double T, double k1, double k2, double k3,
                                  double last_k) {
  const double T2 = T * T, T3 = T2 * T, T4 = T3 * T;
  Eigen::MatrixXd R(6, 6);
  // clang-format off
  R << T4 / 4 * k1 * k1, T3 / 2 * k1 * k1, 0, 0, 0, 0,
       T3 / 2 * k1 * k1, T2 * k1 * k1,     0, 0, 0, 0,
       0, 0, T4 / 4 * k2 * k2, T3 / 2 * k2 * k2, 0, 0,
       0, 0, T3 / 2 * k2 * k2, T2 * k2 * k2,     0, 0,
       0, 0, 0, 0, T4 / 4 * k3 * k3, T3 / 2 * k3 * k3,
       0, 0, 0, 0, T3 / 2 * k3 * k3, T2 * last_k * last_k;
  // clang-format on
  return R;
}

TEST(WhiteAccelerationModel, ProcessNoiseIsTheNotesMatrixWithK3Last) {
  const double T = 0.05, k1 = 0.7, k2 = 1.3, k3 = 2.1;
  const Eigen::MatrixXd ours = ProcessNoise(T, {k1, k2, k3});
  const Eigen::MatrixXd notes = NotesProcessNoise(T, k1, k2, k3, k3);
  ASSERT_EQ(ours.rows(), 6);
  ASSERT_EQ(ours.cols(), 6);
  for (int r = 0; r < 6; ++r) {
    for (int c = 0; c < 6; ++c) {
      EXPECT_NEAR(ours(r, c), notes(r, c), 1e-15) << "entry " << r << "," << c;
    }
  }
}

// The notes' literal last entry (T^2 k2^2) makes the theta block
// k3^2 T^4/4 * T^2 k2^2 - (k3^2 T^3/2)^2 < 0 for k2 < k3: not a covariance.
// Ours is k3^2 G G^T, positive semi-definite for any k.
TEST(WhiteAccelerationModel, NotesLiteralLastEntryIsNotACovariance) {
  const double T = 0.05, k1 = 0.7, k2 = 1.3, k3 = 2.1;
  const Eigen::MatrixXd literal = NotesProcessNoise(T, k1, k2, k3, k2);
  EXPECT_LT(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(literal)
                .eigenvalues()
                .minCoeff(),
            -1e-9);
  const Eigen::MatrixXd ours = ProcessNoise(T, {k1, k2, k3});
  EXPECT_GE(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(ours)
                .eigenvalues()
                .minCoeff(),
            -1e-18);
  EXPECT_GT((ours - literal).cwiseAbs().maxCoeff(), 1e-6);
}

// The model's R_t is the covariance of G a for a ~ N(0, k^2): sampled.
TEST(WhiteAccelerationModel, ProcessNoiseIsTheSampledCovariance) {
  const double T = 0.1, k = 1.7;
  std::mt19937 rng(3);
  std::normal_distribution<double> accel(0.0, k);
  Eigen::Matrix2d sum = Eigen::Matrix2d::Zero();
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    // The state after one step from rest, under a held acceleration.
    const double a = accel(rng);
    const Eigen::Vector2d x(0.5 * a * T * T, a * T);
    sum += x * x.transpose();
  }
  const Eigen::Matrix2d sampled = sum / n;
  const Eigen::Matrix2d R = AxisProcessNoise(T, k);
  for (int r = 0; r < 2; ++r) {
    for (int c = 0; c < 2; ++c) {
      EXPECT_NEAR(sampled(r, c), R(r, c), 0.01 * R(r, c));  // ~ 5 sigma
    }
  }
}

// Kalata's closed form for the discrete white-noise-acceleration model
// (Bar-Shalom, Li, Kirubarajan, "Estimation with Applications to Tracking
// and Navigation", 2001, sec. 6.5.3): with the tracking index
// lambda = k T^2 / sigma, the steady-state gain is (alpha, beta / T) with
//   alpha = -(lambda^2 + 8 lambda - (lambda + 4) sqrt(lambda^2 + 8 lambda))/8
//   beta  =  (lambda^2 + 4 lambda - lambda sqrt(lambda^2 + 8 lambda)) / 4.
TEST(KalmanFilter, SteadyStateGainsAreTheAlphaBetaGains) {
  const double T = 0.05, sigma = 0.02;
  for (double lambda : {0.01, 0.2, 1.0, 5.0}) {
    const double k = lambda * sigma / (T * T);
    KalmanFilter filter(Eigen::Vector2d::Zero(), Eigen::Matrix2d::Identity());
    Eigen::MatrixXd H(1, 2);
    H << 1.0, 0.0;
    const Eigen::MatrixXd Q = Eigen::MatrixXd::Constant(1, 1, sigma * sigma);
    KalmanUpdateInfo info;
    for (int i = 0; i < 5000; ++i) {
      filter.Predict(AxisTransition(T), AxisProcessNoise(T, k));
      info = filter.Update(Eigen::VectorXd::Zero(1), H, Q);
    }
    const double r = std::sqrt(lambda * lambda + 8.0 * lambda);
    const double alpha =
        -(lambda * lambda + 8.0 * lambda - (lambda + 4.0) * r) / 8.0;
    const double beta = (lambda * lambda + 4.0 * lambda - lambda * r) / 4.0;
    EXPECT_NEAR(info.K(0, 0), alpha, 1e-9 * (1.0 + alpha))
        << "lambda " << lambda;
    EXPECT_NEAR(info.K(1, 0) * T, beta, 1e-9 * (1.0 + beta))
        << "lambda " << lambda;
  }
}

Eigen::MatrixXd RandomSpd(int n, std::mt19937* rng) {
  std::normal_distribution<double> normal;
  Eigen::MatrixXd M(n, n);
  for (int i = 0; i < n * n; ++i) M(i) = normal(*rng);
  return M * M.transpose() + 0.1 * Eigen::MatrixXd::Identity(n, n);
}

// With the optimal gain, Joseph's form equals the notes' (E - K) Sigma_bar
// (H = E) and (E - K H) Sigma_bar in general.
TEST(KalmanFilter, JosephFormEqualsTheNotesCovarianceUpdate) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 20; ++trial) {
    const int n = 6;
    const int m = trial % 2 == 0 ? n : 3;  // the notes' H = E, then general
    const Eigen::MatrixXd sigma_bar = RandomSpd(n, &rng);
    const Eigen::MatrixXd Q = RandomSpd(m, &rng);
    Eigen::MatrixXd H = Eigen::MatrixXd::Identity(n, n);
    if (m != n) H = Eigen::MatrixXd::Random(m, n);
    KalmanFilter filter(Eigen::VectorXd::Zero(n), sigma_bar);
    const KalmanUpdateInfo info =
        m == n ? filter.Update(Eigen::VectorXd::Ones(n), Q)
               : filter.Update(Eigen::VectorXd::Ones(m), H, Q);
    // The notes' gain and covariance, written directly.
    const Eigen::MatrixXd K = sigma_bar * H.transpose() *
                              (H * sigma_bar * H.transpose() + Q).inverse();
    const Eigen::MatrixXd notes =
        (Eigen::MatrixXd::Identity(n, n) - K * H) * sigma_bar;
    EXPECT_LT((info.K - K).cwiseAbs().maxCoeff(), 1e-9);
    EXPECT_LT((filter.covariance() - notes).cwiseAbs().maxCoeff(),
              1e-9 * sigma_bar.cwiseAbs().maxCoeff())
        << "trial " << trial;
  }
}

TEST(KalmanFilter, WrapToPiMapsIntoTheHalfOpenInterval) {
  EXPECT_DOUBLE_EQ(WrapToPi(M_PI), M_PI);
  EXPECT_DOUBLE_EQ(WrapToPi(-M_PI), M_PI);
  EXPECT_NEAR(WrapToPi(3.0 * M_PI), M_PI, 1e-12);
  EXPECT_NEAR(WrapToPi(-0.5 * M_PI + 4.0 * M_PI), -0.5 * M_PI, 1e-12);
  EXPECT_NEAR(WrapToPi(0.1), 0.1, 0.0);
}

// A yaw of +179 deg predicted, -179 deg measured: a +2 deg innovation.
TEST(KalmanFilter, AngleInnovationsAreWrapped) {
  const double deg = M_PI / 180.0;
  KalmanFilter filter(Eigen::VectorXd::Constant(1, 179.0 * deg),
                      Eigen::MatrixXd::Identity(1, 1));
  const KalmanUpdateInfo info = filter.Update(
      Eigen::VectorXd::Constant(1, -179.0 * deg),
      Eigen::MatrixXd::Identity(1, 1), Eigen::MatrixXd::Identity(1, 1), {0});
  EXPECT_NEAR(info.innovation(0), 2.0 * deg, 1e-12);
  EXPECT_NEAR(filter.mean()(0), 180.0 * deg, 1e-12);  // halfway, unwrapped
}

TEST(KalmanFilter, RejectsSizesThatDoNotFit) {
  KalmanFilter filter(Eigen::VectorXd::Zero(2),
                      Eigen::MatrixXd::Identity(2, 2));
  EXPECT_THROW(filter.Predict(Eigen::MatrixXd::Identity(3, 3),
                              Eigen::MatrixXd::Zero(2, 2)),
               std::invalid_argument);
  EXPECT_THROW(
      filter.Update(Eigen::VectorXd::Zero(1), Eigen::MatrixXd::Identity(1, 1)),
      std::invalid_argument);
  EXPECT_THROW(
      KalmanFilter(Eigen::VectorXd::Zero(2), Eigen::MatrixXd::Identity(3, 3)),
      std::invalid_argument);
}

// Monte-Carlo runs of the notes' planar model itself (truth drawn from the
// same A, R_t, Q_t): for a consistent filter the NEES averaged over M runs,
// times M, is chi-square with M n degrees of freedom at every step, and the
// NIS summed over runs and steps is chi-square with M K m (innovations are
// white). Both must sit inside their two-sided 95 % bands.
struct Consistency {
  double fraction_nees_inside = 0.0;  // of the steps
  double nis_sum = 0.0;
  double nis_low = 0.0, nis_high = 0.0;
};

Consistency RunMonteCarlo(bool measure_whole_state) {
  const int runs = 100, steps = 100, n = 6;
  const double T = 0.05, k1 = 0.8, k2 = 1.5, k3 = 2.5;
  const Eigen::MatrixXd A = Transition(3, T);
  const Eigen::MatrixXd R = ProcessNoise(T, {k1, k2, k3});
  Eigen::MatrixXd H = Eigen::MatrixXd::Identity(n, n);
  if (!measure_whole_state) {  // X, Z, theta only
    H = Eigen::MatrixXd::Zero(3, n);
    for (int i = 0; i < 3; ++i) H(i, 2 * i) = 1.0;
  }
  const int m = static_cast<int>(H.rows());
  Eigen::VectorXd q_sigma(m);
  for (int i = 0; i < m; ++i) q_sigma(i) = 0.02 + 0.01 * i;
  const Eigen::MatrixXd Q = q_sigma.cwiseAbs2().asDiagonal();
  const Eigen::MatrixXd sigma0 = 0.01 * Eigen::MatrixXd::Identity(n, n);
  // Process noise as the model makes it: w = G a per axis, a ~ N(0, k^2).
  Eigen::MatrixXd L_R = Eigen::MatrixXd::Zero(n, 3);
  const double k[3] = {k1, k2, k3};
  for (int i = 0; i < 3; ++i) {
    L_R(2 * i, i) = 0.5 * T * T * k[i];
    L_R(2 * i + 1, i) = T * k[i];
  }
  const Eigen::MatrixXd L_0 = sigma0.llt().matrixL();

  std::mt19937 rng(2024);
  std::normal_distribution<double> normal;
  auto draw = [&](int size) {
    Eigen::VectorXd v(size);
    for (int i = 0; i < size; ++i) v(i) = normal(rng);
    return v;
  };
  std::vector<double> nees_sum(steps, 0.0);
  Consistency out;
  for (int run = 0; run < runs; ++run) {
    Eigen::VectorXd x = L_0 * draw(n);
    KalmanFilter filter(Eigen::VectorXd::Zero(n), sigma0);
    for (int k = 0; k < steps; ++k) {
      x = A * x + L_R * draw(3);
      const Eigen::VectorXd z = H * x + q_sigma.cwiseProduct(draw(m));
      filter.Predict(A, R);
      out.nis_sum += filter.Update(z, H, Q).nis;
      const Eigen::VectorXd e = x - filter.mean();
      nees_sum[k] += e.dot(filter.covariance().ldlt().solve(e));
    }
  }
  const double low = ChiSquareQuantile(runs * n, -kZ975);
  const double high = ChiSquareQuantile(runs * n, kZ975);
  int inside = 0;
  for (double s : nees_sum) inside += (s >= low && s <= high) ? 1 : 0;
  out.fraction_nees_inside = static_cast<double>(inside) / steps;
  out.nis_low = ChiSquareQuantile(runs * steps * m, -kZ975);
  out.nis_high = ChiSquareQuantile(runs * steps * m, kZ975);
  return out;
}

TEST(KalmanFilter, NeesAndNisInsideTheirChiSquareBandsWholeState) {
  const Consistency c = RunMonteCarlo(/*measure_whole_state=*/true);
  EXPECT_GE(c.fraction_nees_inside, 0.9);  // 95 % expected
  EXPECT_GT(c.nis_sum, c.nis_low);
  EXPECT_LT(c.nis_sum, c.nis_high);
}

TEST(KalmanFilter, NeesAndNisInsideTheirChiSquareBandsPositionsOnly) {
  const Consistency c = RunMonteCarlo(/*measure_whole_state=*/false);
  EXPECT_GE(c.fraction_nees_inside, 0.9);
  EXPECT_GT(c.nis_sum, c.nis_low);
  EXPECT_LT(c.nis_sum, c.nis_high);
}

// The quantile helper against table values (Abramowitz & Stegun, table 26.8).
TEST(ChiSquare, WilsonHilfertyMatchesTableValues) {
  EXPECT_NEAR(ChiSquareQuantile(100, kZ975), 129.561, 0.02);
  EXPECT_NEAR(ChiSquareQuantile(100, -kZ975), 74.222, 0.02);
  EXPECT_NEAR(ChiSquareQuantile(30, kZ975), 46.979, 0.02);
  EXPECT_NEAR(ChiSquareQuantile(30, -kZ975), 16.791, 0.02);
}

}  // namespace
}  // namespace vio
