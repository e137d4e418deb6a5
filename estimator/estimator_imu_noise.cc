// Estimator: the online IMU white-noise scale
// (estimator/imu_noise_adaptation.h).

#include <stdexcept>

#include "estimator/estimator.h"
#include "factors/imu_factor.h"

namespace vio {

void Estimator::AdaptImuNoise() {
  if (!options_.imu_stream.noise_adaptation.enabled) return;
  const auto& frames = window_.frames;
  if (frames.size() < 2) return;
  ImuChi2Sums sums;
  for (size_t k = 1; k < frames.size(); ++k) {
    const WindowFrame& i = *frames[k - 1];
    const WindowFrame& j = *frames[k];
    // Never across an IMU gap: a visual link carries no IMU residual, and
    // the states around it are not what the IMU says.
    if (!j.imu) return;
    Vector15d residual;
    try {
      const ImuFactor factor(j.imu->result(), options_.gravity_magnitude);
      const double* blocks[] = {i.pose.data(), i.speed_bias.data(),
                                j.pose.data(), j.speed_bias.data()};
      if (!factor.UnweightedResidual(blocks, &residual)) return;
    } catch (const std::invalid_argument&) {
      return;  // a covariance that is not positive definite: no estimate
    }
    if (!AddImuChi2(residual, j.imu->result(), j.imu->noise(), noise_, &sums)) {
      return;
    }
  }
  noise_adaptation_.Update(sums);
  summary_.imu_noise_updates = noise_adaptation_.updates();
  summary_.imu_noise_scale_accelerometer =
      noise_adaptation_.accelerometer_scale();
  summary_.imu_noise_scale_gyroscope = noise_adaptation_.gyroscope_scale();
}

}  // namespace vio
