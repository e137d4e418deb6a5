#ifndef VIO_ESTIMATOR_STATE_PRIOR_H_
#define VIO_ESTIMATOR_STATE_PRIOR_H_

// A Gaussian prior on one frame's pose and speed-bias, in the form of the
// marginalisation prior (r = r0 + J (x (-) x0), here r0 = 0), so that the
// window treats it like any prior and folds it into the next one.
//
// Rotation: the tangent is the right (body-frame) perturbation dtheta, but the
// uncertainty is stated about world axes: yaw about world z, tilt about the
// horizontal. With u = R_w_b^T e_z (world z seen in the body),
//   Lambda_rot = (I - u u^T) / sigma_tilt^2 + u u^T / sigma_yaw^2,
// and J_rot = L^T with Lambda_rot = L L^T, so that J^T J = Lambda.

#include <memory>
#include <vector>

#include "estimator/estimator_options.h"
#include "factors/marginalization_prior.h"

namespace vio {

// pose: 7 values [t, q (x, y, z, w)], speed_bias: 9 [v, b_a, b_g], both
// finite; they become x0. The prior's blocks are (pose, speed_bias).
std::unique_ptr<MarginalizationPrior> MakeStatePrior(
    const double* pose, const double* speed_bias,
    const StatePriorOptions& sigmas, double velocity_sigma);

// A Gaussian prior on camera extrinsics T_b_c (7 values each, [t, q]), every
// one at its current value: the tangent [dt, dtheta] of each gets
// diag(sigma_t^2 I, sigma_rot^2 I). Its blocks are the extrinsics in order;
// `extrinsics` must not be empty and every value finite.
std::unique_ptr<MarginalizationPrior> MakeExtrinsicPrior(
    const std::vector<const double*>& extrinsics,
    const StatePriorOptions& sigmas);

// A Gaussian prior on the biases of one speed-bias block (9 values [v, b_a,
// b_g], finite) at their current values, the velocity left free: J is 6 x 9,
// zero in the velocity columns, diag(1 / sigma_ba, 1 / sigma_bg) in the bias
// ones.
std::unique_ptr<MarginalizationPrior> MakeBiasPrior(const double* speed_bias,
                                                    double accel_bias_sigma,
                                                    double gyro_bias_sigma);

// The bias random walk between two speed-bias blocks i and j (finite), what
// an IMU factor between them would carry and nothing else:
//   r = W ([b_a, b_g]_j - [b_a, b_g]_i),  W = diag(1 / sigma_ba, 1 / sigma_bg)
// (linear, so exact in the prior's form r0 + J (x - x0)). Across an IMU gap
// it ties the biases after the gap to those before (estimator/imu_gaps.h).
std::unique_ptr<MarginalizationPrior> MakeBiasLink(const double* speed_bias_i,
                                                   const double* speed_bias_j,
                                                   double accel_bias_sigma,
                                                   double gyro_bias_sigma);

}  // namespace vio

#endif  // VIO_ESTIMATOR_STATE_PRIOR_H_
