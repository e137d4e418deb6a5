#ifndef VIO_ESTIMATOR_IMAGE_VELOCITY_H_
#define VIO_ESTIMATOR_IMAGE_VELOCITY_H_

// Image velocity of a landmark predicted from the estimated motion, for the
// time-offset factor (TimedReprojectionFactor).
//
// Why not the tracker's finite difference: v_k = (xy_k - xy_(k-1)) / dt holds
// the pixel noise of xy_k amplified by 1 / dt, and the timed residual
//   xy_j - (t_d - t_d_j) v_j
// then lets t_d cancel part of that noise (errors in variables): measured on
// config/sim_aggressive.yaml (1 px noise) it ran to the +-0.02 s bound. The
// velocity of the two previous observations has the same flaw whenever the
// anchor is the frame just before (v_j then holds the anchor's noise with the
// opposite sign, drawing t_d towards -dt). The motion gives a velocity that
// shares no pixel noise with the residual.
//
// With the point p_c in the camera (normalised xy = p_c.xy / p_c.z), the body
// angular rate w_b, the body velocity v_w and T_w_b, T_b_c:
//   w_c = R_c_b w_b,   v_w_c = v_w + R_w_b (w_b x t_b_c),
//   d p_c / dt = -w_c x p_c - R_c_w v_w_c,
//   d xy / dt = (d p_c.xy - xy * d p_c.z) / p_c.z.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "preintegration/imu_types.h"

namespace vio {

// d xy / dt [1/s] of the point p_c [m] (in camera c, z > 0) seen from a body
// at T_w_b moving with v_w [m/s] and turning with w_b [rad/s] (gyroscope
// minus bias, body frame). Zero when p_c is not finite or p_c.z is not
// positive.
Eigen::Vector2d PredictedImageVelocity(const Eigen::Vector3d& p_c,
                                       const Eigen::Isometry3d& T_w_b,
                                       const Eigen::Vector3d& v_w,
                                       const Eigen::Vector3d& w_b,
                                       const Eigen::Isometry3d& T_b_c);

// The gyroscope reading at t_ns [rad/s] (bias not removed), linearly
// interpolated between the samples around it (the nearest one at either
// end; zero for an empty buffer): the angular rate at a frame's stamp. imu is
// sorted by stamp.
Eigen::Vector3d GyroscopeAt(const std::vector<ImuSample>& imu, int64_t t_ns);

}  // namespace vio

#endif  // VIO_ESTIMATOR_IMAGE_VELOCITY_H_
