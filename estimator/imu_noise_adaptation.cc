#include "estimator/imu_noise_adaptation.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

namespace vio {
namespace {

// Rows of the preintegration residual (PreintegratedImu::covariance order).
constexpr int kP = 0, kTheta = 3, kV = 6;

// r^T Sigma^-1 r by a Cholesky of Sigma; false when Sigma is not positive
// definite or the result is not finite.
template <int N>
bool Chi2(const Eigen::Matrix<double, N, 1>& r,
          const Eigen::Matrix<double, N, N>& sigma, double* chi2) {
  const Eigen::LLT<Eigen::Matrix<double, N, N>> llt(sigma);
  if (llt.info() != Eigen::Success) return false;
  // Sigma = L L^T, so r^T Sigma^-1 r = |L^-1 r|^2.
  *chi2 = llt.matrixL().solve(r).squaredNorm();
  return std::isfinite(*chi2);
}

}  // namespace

bool ImuNoiseAdaptationOptions::Validate(std::string* message) const {
  if (!(smoothing > 0.0 && smoothing <= 1.0)) {
    *message =
        "smoothing must be in (0, 1] (got " + std::to_string(smoothing) + ")";
    return false;
  }
  if (!(min_scale > 0.0 && min_scale <= 1.0)) {
    *message =
        "min_scale must be in (0, 1] (got " + std::to_string(min_scale) + ")";
    return false;
  }
  if (!(max_scale >= 1.0 && std::isfinite(max_scale))) {
    *message = "max_scale must be finite and >= 1 (got " +
               std::to_string(max_scale) + ")";
    return false;
  }
  return true;
}

bool AddImuChi2(const Vector15d& residual,
                const PreintegratedImu& preintegrated, const ImuNoise& used,
                const ImuNoise& configured, ImuChi2Sums* sums) {
  const Matrix15d& sigma = preintegrated.covariance;
  // Group A: the dp and dv rows with their cross-covariance.
  Eigen::Matrix<double, 6, 1> r_a;
  r_a << residual.segment<3>(kP), residual.segment<3>(kV);
  Eigen::Matrix<double, 6, 6> sigma_a;
  sigma_a << sigma.block<3, 3>(kP, kP), sigma.block<3, 3>(kP, kV),
      sigma.block<3, 3>(kV, kP), sigma.block<3, 3>(kV, kV);
  const Eigen::Vector3d r_g = residual.segment<3>(kTheta);
  const Eigen::Matrix3d sigma_g = sigma.block<3, 3>(kTheta, kTheta);
  double chi2_a = 0.0, chi2_g = 0.0;
  if (!Chi2<6>(r_a, sigma_a, &chi2_a) || !Chi2<3>(r_g, sigma_g, &chi2_g)) {
    return false;
  }
  // s_used = used density / configured density, per sensor.
  const double s_a =
      used.accelerometer_noise_density / configured.accelerometer_noise_density;
  const double s_g =
      used.gyroscope_noise_density / configured.gyroscope_noise_density;
  sums->accelerometer += s_a * s_a * chi2_a;
  sums->accelerometer_rows += 6;
  sums->gyroscope += s_g * s_g * chi2_g;
  sums->gyroscope_rows += 3;
  return true;
}

void ImuNoiseAdaptation::Update(const ImuChi2Sums& sums) {
  const double w = options_.smoothing;
  bool updated = false;
  if (sums.accelerometer_rows > 0) {
    accelerometer_variance_ratio_ +=
        w * (sums.accelerometer / sums.accelerometer_rows -
             accelerometer_variance_ratio_);
    updated = true;
  }
  if (sums.gyroscope_rows > 0) {
    gyroscope_variance_ratio_ +=
        w * (sums.gyroscope / sums.gyroscope_rows - gyroscope_variance_ratio_);
    updated = true;
  }
  // The average stays within the clamp, so that it comes back at once.
  const double lo = options_.min_scale * options_.min_scale;
  const double hi = options_.max_scale * options_.max_scale;
  accelerometer_variance_ratio_ =
      std::clamp(accelerometer_variance_ratio_, lo, hi);
  gyroscope_variance_ratio_ = std::clamp(gyroscope_variance_ratio_, lo, hi);
  if (updated) ++updates_;
}

double ImuNoiseAdaptation::Clamped(double variance_ratio) const {
  return std::clamp(std::sqrt(variance_ratio), options_.min_scale,
                    options_.max_scale);
}

double ImuNoiseAdaptation::accelerometer_scale() const {
  return Clamped(accelerometer_variance_ratio_);
}

double ImuNoiseAdaptation::gyroscope_scale() const {
  return Clamped(gyroscope_variance_ratio_);
}

ImuNoise ImuNoiseAdaptation::Scaled(const ImuNoise& configured) const {
  if (!options_.enabled) return configured;
  ImuNoise scaled = configured;
  scaled.accelerometer_noise_density *= accelerometer_scale();
  scaled.gyroscope_noise_density *= gyroscope_scale();
  return scaled;
}

}  // namespace vio
