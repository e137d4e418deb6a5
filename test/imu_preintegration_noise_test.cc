// The propagated covariance against Monte-Carlo: many integrations of the
// same motion with sensor noise drawn per sample, as a real IMU has it.

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <random>
#include <vector>

#include "geometry/so3.h"
#include "preintegration/imu_preintegration.h"
#include "test/testing/analytic_trajectory.h"

namespace vio {
namespace {

constexpr int64_t kPeriodNs = 5000000;  // 200 Hz
constexpr int64_t kT0Ns = 1000000000;
constexpr int64_t kT1Ns = kT0Ns + 500000000;
constexpr int kRuns = 4000;
const Eigen::Vector3d kBa(0.1, -0.05, 0.08);
const Eigen::Vector3d kBg(0.01, 0.003, -0.006);

// One noisy realisation: white noise sigma / sqrt(h) on every sample and a
// bias random walk sigma * sqrt(h) per sample, starting from the
// linearisation biases at t0 (DESIGN.md noise units). Returns the error
// truth - estimate in the error state [dp, dth, dv, db_a, db_g].
Vector15d NoisyRunError(const std::vector<ImuSample>& clean,
                        const ImuDelta& truth, const ImuNoise& noise,
                        std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  const auto gauss3 = [&] { return Eigen::Vector3d(n(rng), n(rng), n(rng)); };
  const double h = 1e-9 * kPeriodNs;
  Eigen::Vector3d walk_a = Eigen::Vector3d::Zero();
  Eigen::Vector3d walk_g = Eigen::Vector3d::Zero();
  std::vector<ImuSample> noisy = clean;
  for (size_t k = 0; k < noisy.size(); ++k) {
    if (k > 0) {
      walk_a += noise.accelerometer_random_walk * std::sqrt(h) * gauss3();
      walk_g += noise.gyroscope_random_walk * std::sqrt(h) * gauss3();
    }
    noisy[k].acc +=
        walk_a + noise.accelerometer_noise_density / std::sqrt(h) * gauss3();
    noisy[k].gyr +=
        walk_g + noise.gyroscope_noise_density / std::sqrt(h) * gauss3();
  }
  ImuDelta estimate;
  for (size_t k = 0; k + 1 < noisy.size(); ++k) {
    estimate = MidpointStep(estimate, noisy[k], noisy[k + 1], kBa, kBg);
  }
  Vector15d e;
  e.segment<3>(kImuP) = truth.p - estimate.p;
  e.segment<3>(kImuR) = Log(estimate.q.conjugate() * truth.q);
  e.segment<3>(kImuV) = truth.v - estimate.v;
  e.segment<3>(kImuBa) = walk_a;
  e.segment<3>(kImuBg) = walk_g;
  return e;
}

struct MonteCarlo {
  Matrix15d sample_covariance;  // normalised by n - 1
  std::vector<Vector15d> errors;
};

MonteCarlo RunMonteCarlo(const ImuNoise& noise) {
  const testing::AnalyticTrajectory traj;
  const std::vector<ImuSample> clean =
      traj.Samples(kT0Ns, kT1Ns, kPeriodNs, kBa, kBg);
  ImuDelta truth;
  for (size_t k = 0; k + 1 < clean.size(); ++k) {
    truth = MidpointStep(truth, clean[k], clean[k + 1], kBa, kBg);
  }
  std::mt19937 rng(42);
  MonteCarlo mc;
  Vector15d mean = Vector15d::Zero();
  for (int i = 0; i < kRuns; ++i) {
    mc.errors.push_back(NoisyRunError(clean, truth, noise, rng));
    mean += mc.errors.back() / kRuns;
  }
  mc.sample_covariance.setZero();
  for (const Vector15d& e : mc.errors) {
    mc.sample_covariance += (e - mean) * (e - mean).transpose();
  }
  mc.sample_covariance /= kRuns - 1;
  return mc;
}

// Computed once (about 0.4 s) and shared by the tests.
const MonteCarlo& AdisMonteCarlo() {
  static const MonteCarlo mc = RunMonteCarlo(ImuNoise());
  return mc;
}

Matrix15d PropagatedCovariance(const ImuNoise& noise) {
  const testing::AnalyticTrajectory traj;
  const ImuPreintegration pre(kT0Ns, kT1Ns,
                              traj.Samples(kT0Ns, kT1Ns, kPeriodNs, kBa, kBg),
                              kBa, kBg, noise, PreintegrationOptions());
  return pre.covariance();
}

// Mean over the runs of e^T P^-1 e: 15 when P is right, with standard
// deviation sqrt(2 * 15 / n) (chi-squared with 15 degrees of freedom).
double MeanChiSquared(const MonteCarlo& mc, const Matrix15d& P) {
  const Eigen::LLT<Matrix15d> llt(P);
  double sum = 0.0;
  for (const Vector15d& e : mc.errors) sum += e.dot(llt.solve(e));
  return sum / mc.errors.size();
}

TEST(ImuPreintegrationNoise, CovarianceMatchesMonteCarlo) {
  const MonteCarlo& mc = AdisMonteCarlo();  // EuRoC's ADIS16448
  const Matrix15d P = PropagatedCovariance(ImuNoise());

  // Whitened sample covariance W = L^-1 S L^-T with P = L L^T. If P is the
  // true covariance, (n - 1) W is Wishart(I, n - 1): diagonal entries have
  // mean 1 and standard deviation sqrt(2 / (n - 1)) (4.5 %), off-diagonal
  // entries mean 0 and sqrt(1 / (n - 1)) (3.2 %). Whitening makes every
  // entry comparable whatever the scale and correlation of the original
  // blocks. Each of the 120 distinct entries must lie within 5 standard
  // deviations (a false alarm anywhere: about 1e-4 under the Gaussian limit).
  const Eigen::LLT<Matrix15d> llt(P);
  ASSERT_EQ(llt.info(), Eigen::Success);
  const Matrix15d L = llt.matrixL();
  const Matrix15d L_inv = L.inverse();
  const Matrix15d W = L_inv * mc.sample_covariance * L_inv.transpose();
  const double sd_diag = std::sqrt(2.0 / (kRuns - 1));
  const double sd_off = std::sqrt(1.0 / (kRuns - 1));
  for (int i = 0; i < 15; ++i) {
    EXPECT_NEAR(W(i, i), 1.0, 5 * sd_diag) << "diagonal " << i;
    for (int j = 0; j < i; ++j) {
      EXPECT_NEAR(W(i, j), 0.0, 5 * sd_off) << "entry " << i << ", " << j;
    }
  }
  // Mean chi-squared within 5 standard deviations of 15 (0.43 for n = 4000);
  // measured 14.96.
  EXPECT_NEAR(MeanChiSquared(mc, P), 15.0, 5 * std::sqrt(30.0 / kRuns));
}

TEST(ImuPreintegrationNoise, HalvedWhiteNoiseVarianceIsDetected) {
  // The statistic has the power to see VINS-Mono's per-endpoint sigma^2 / dt,
  // which halves the white-noise variance: propagate with the densities
  // divided by sqrt(2) and the mean chi-squared leaves the band (measured
  // 23.6).
  ImuNoise halved;
  halved.accelerometer_noise_density /= std::sqrt(2.0);
  halved.gyroscope_noise_density /= std::sqrt(2.0);
  EXPECT_GT(MeanChiSquared(AdisMonteCarlo(), PropagatedCovariance(halved)),
            15.0 + 5 * std::sqrt(30.0 / kRuns));
}

}  // namespace
}  // namespace vio
