#ifndef VIO_ESTIMATOR_IMU_NOISE_ADAPTATION_H_
#define VIO_ESTIMATOR_IMU_NOISE_ADAPTATION_H_

// Online scale of the IMU white-noise densities from the window itself
// (variance component estimation; Koch, "Parameter Estimation and Hypothesis
// Testing in Linear Models", sec. 3.6, in its simplest form: one variance
// factor per group, estimated as chi^2 / rows).
//
// After each solve the IMU factors' residuals r (preintegration order
// [dp, dth, dv, db_a, db_g]) are split into two groups and weighted by the
// matching block of the interval's own covariance Sigma:
//   accelerometer group A = rows dp, dv (6):  chi^2_A = r_A^T Sigma_AA^-1 r_A
//   gyroscope group G     = rows dth (3):      chi^2_G = r_G^T Sigma_GG^-1 r_G
// If the densities used were s_used times the configured ones and the true
// ones are s times, E[chi^2 / rows] = (s / s_used)^2, so each step estimates
//   s^2 = s_used^2 * chi^2 / rows,
// averaged over the window's intervals (each with its own s_used). The
// variance ratio s^2 is smoothed by an exponential average over many steps
// and the density scale s = sqrt(average) is clamped to [min_scale,
// max_scale]; the NEXT intervals are preintegrated with the configured
// densities times s (accelerometer and gyroscope separately).
//
// Known bias: the residuals are those after the fit, whose states absorb
// part of them (the velocities and biases above all), so chi^2 / rows
// underestimates the ratio by the window's redundancy; no correction is
// made (docs/recorded_flights.md measures what the scale reaches). The dp,
// dv rows also carry the gyroscope's noise through the rotation, so group A
// is not purely the accelerometer's.
//
// The estimator updates it only after a successful step of an initialised
// window whose frames are all linked by the IMU (never across a reset or an
// IMU gap); the scale survives resets (it describes the sensor).

#include <string>

#include "preintegration/imu_preintegration.h"
#include "preintegration/imu_types.h"

namespace vio {

struct ImuNoiseAdaptationOptions {
  bool enabled = false;  // off: the configured densities throughout
  // Weight of one step's estimate in the exponential average (0, 1]: 0.02
  // averages over about 50 steps (2.5 s at 20 Hz).
  double smoothing = 0.02;
  // The density scale stays within [min_scale, max_scale] of the configured
  // densities (0 < min_scale <= 1 <= max_scale).
  double min_scale = 0.5;
  double max_scale = 3.0;

  // True when every field is in range; otherwise false with a message that
  // starts with the offending field's name.
  bool Validate(std::string* message) const;
};

// chi^2 sums and row counts of the two groups over some intervals, each
// already multiplied by the interval's s_used^2 (the header's formula).
struct ImuChi2Sums {
  double accelerometer = 0.0;  // sum of s_used_a^2 * chi^2_A [-]
  int accelerometer_rows = 0;
  double gyroscope = 0.0;  // sum of s_used_g^2 * chi^2_G [-]
  int gyroscope_rows = 0;
};

// Adds one interval's residual to `sums`. `residual` is the unweighted IMU
// factor residual, `preintegrated` the interval it belongs to, built with
// the densities `used` (configured times s_used). Returns false (and adds
// nothing) when a block of the covariance is not positive definite or the
// residual is not finite.
bool AddImuChi2(const Vector15d& residual,
                const PreintegratedImu& preintegrated, const ImuNoise& used,
                const ImuNoise& configured, ImuChi2Sums* sums);

class ImuNoiseAdaptation {
 public:
  explicit ImuNoiseAdaptation(const ImuNoiseAdaptationOptions& options)
      : options_(options) {}

  // One step's sums: moves each group's averaged variance ratio towards
  // sums / rows by `smoothing` (a group without rows is left as it is).
  void Update(const ImuChi2Sums& sums);

  // The densities for the next intervals: `configured` with its white-noise
  // densities times the clamped scales (random walks unchanged), or
  // `configured` itself when the adaptation is off.
  ImuNoise Scaled(const ImuNoise& configured) const;

  // The clamped density scales [-] (1 before any update).
  double accelerometer_scale() const;
  double gyroscope_scale() const;
  int updates() const { return updates_; }

 private:
  double Clamped(double variance_ratio) const;

  ImuNoiseAdaptationOptions options_;
  double accelerometer_variance_ratio_ = 1.0;
  double gyroscope_variance_ratio_ = 1.0;
  int updates_ = 0;
};

}  // namespace vio

#endif  // VIO_ESTIMATOR_IMU_NOISE_ADAPTATION_H_
