#ifndef VIO_PREINTEGRATION_MIDPOINT_STEP_H_
#define VIO_PREINTEGRATION_MIDPOINT_STEP_H_

// One step of midpoint IMU preintegration, with the exact Jacobians of the
// discrete step (the error-state transition F and the noise input G).
//
// The preintegrated terms live in the body frame b_i of the interval's start:
//   delta_p, delta_v: what R_w_bi^T (p, v) gains from the specific force alone
//   delta_q:          rotation of the current body frame in b_i.
// A step from sample k to k+1 (dt = t_{k+1} - t_k [s], biases held constant):
//   w      = (w_k + w_{k+1}) / 2 - b_g
//   q_{k+1} = q_k (x) Exp(w dt)
//   a      = (R_k (a_k - b_a) + R_{k+1} (a_{k+1} - b_a)) / 2
//   p_{k+1} = p_k + v_k dt + a dt^2 / 2
//   v_{k+1} = v_k + a dt
// This is VINS-Mono's midpoint scheme (Qin et al., T-RO 2018, sec. IV-B) with
// the exact Exp instead of its first-order quaternion.
//
// Error state (DESIGN.md order, right perturbation):
//   x = [delta_p, delta_theta, delta_v, delta_b_a, delta_b_g] (15),
//   p = p^ + delta_p, R = R^ Exp(delta_theta), v = v^ + delta_v, b = b^ +
//   delta_b.
// Noise (18), each added to the quantity it names:
//   [n_a0, n_g0, n_a1, n_g1] on a_k, w_k, a_{k+1}, w_{k+1};
//   [n_ba, n_bg] the bias random walk over the step, b_{k+1} = b_k + n_b.
// Then x_{k+1} = F x_k + G n to first order. The user's note
// (shared/seeds/001_5f4676e8801b0f44.txt) derives the entries f15 = dp/db_g and
// g12 = dp/dn_g0; midpoint_step.cc derives all of them.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "preintegration/imu_types.h"

namespace vio {

// Slots of the 15-dimensional error state, which is also the IMU residual's
// order (DESIGN.md).
constexpr int kImuP = 0;
constexpr int kImuR = 3;
constexpr int kImuV = 6;
constexpr int kImuBa = 9;
constexpr int kImuBg = 12;
constexpr int kImuErrorSize = 15;

// Slots of the 18-dimensional noise vector of one step.
constexpr int kNoiseAcc0 = 0;
constexpr int kNoiseGyr0 = 3;
constexpr int kNoiseAcc1 = 6;
constexpr int kNoiseGyr1 = 9;
constexpr int kNoiseBa = 12;
constexpr int kNoiseBg = 15;
constexpr int kImuNoiseSize = 18;

using Matrix15d = Eigen::Matrix<double, 15, 15>;
using Matrix15x18d = Eigen::Matrix<double, 15, 18>;
using Vector15d = Eigen::Matrix<double, 15, 1>;

// The preintegrated terms from the interval's start to some sample.
struct ImuDelta {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();            // delta_p [m]
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();  // delta_q (b_i <- b)
  Eigen::Vector3d v = Eigen::Vector3d::Zero();            // delta_v [m/s]
};

// Integrates from sample s0 to sample s1 (ImuError unless s1.t_ns > s0.t_ns)
// with constant biases b_a [m/s^2] and b_g [rad/s]. Optionally returns the
// Jacobians of the step: d_next_d_curr (F, 15 x 15) and d_next_d_noise
// (G, 15 x 18), evaluated at the given state and biases.
ImuDelta MidpointStep(const ImuDelta& curr, const ImuSample& s0,
                      const ImuSample& s1, const Eigen::Vector3d& b_a,
                      const Eigen::Vector3d& b_g,
                      Matrix15d* d_next_d_curr = nullptr,
                      Matrix15x18d* d_next_d_noise = nullptr);

// Diagonal of the covariance of the 18 noise inputs of a step of dt [s].
// White noise: each endpoint sample's noise gets 2 sigma^2 / dt, so that their
// average, which is what the step integrates, has the continuous-time
// variance sigma^2 / dt (see midpoint_step.cc). Random walk: sigma^2 dt.
Eigen::Matrix<double, 18, 1> StepNoiseVariances(const ImuNoise& noise,
                                                double dt);

}  // namespace vio

#endif  // VIO_PREINTEGRATION_MIDPOINT_STEP_H_
