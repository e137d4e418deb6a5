#include "preintegration/midpoint_step.h"

#include <cassert>

#include "geometry/so3.h"

namespace vio {

ImuDelta MidpointStep(const ImuDelta& curr, const ImuSample& s0,
                      const ImuSample& s1, const Eigen::Vector3d& b_a,
                      const Eigen::Vector3d& b_g, Matrix15d* d_next_d_curr,
                      Matrix15x18d* d_next_d_noise) {
  assert(s1.t_ns > s0.t_ns);
  const double dt = 1e-9 * static_cast<double>(s1.t_ns - s0.t_ns);
  const Eigen::Vector3d w = 0.5 * (s0.gyr + s1.gyr) - b_g;
  const Eigen::Vector3d phi = w * dt;
  const Eigen::Matrix3d R_k = curr.q.toRotationMatrix();
  const Eigen::Quaterniond dq = ExpQuaternion(phi);

  ImuDelta next;
  next.q = (curr.q * dq).normalized();
  const Eigen::Matrix3d R_k1 = next.q.toRotationMatrix();
  const Eigen::Vector3d a0 = s0.acc - b_a;
  const Eigen::Vector3d a1 = s1.acc - b_a;
  const Eigen::Vector3d a = 0.5 * (R_k * a0 + R_k1 * a1);
  next.p = curr.p + curr.v * dt + 0.5 * a * dt * dt;
  next.v = curr.v + a * dt;

  if (d_next_d_curr == nullptr && d_next_d_noise == nullptr) return next;

  // Rotation. R_k Exp(dth) Exp(phi) = R_k Exp(phi) Exp(dR^T dth), so
  //   dth_{k+1} = dR^T dth_k.
  // A gyro change e (bias -e, or noise e/2 at either end) moves phi by e dt
  // and Exp(phi + e dt) ~ Exp(phi) Exp(Jr(phi) e dt), so
  //   d dth_{k+1} / d b_g = -Jr dt,   d dth_{k+1} / d n_g0,1 = Jr dt / 2.
  const Eigen::Matrix3d dR_T = dq.toRotationMatrix().transpose();
  const Eigen::Matrix3d Jr_dt = RightJacobian(phi) * dt;
  const Eigen::Matrix3d d_th1_d_th0 = dR_T;
  const Eigen::Matrix3d d_th1_d_bg = -Jr_dt;

  // Mean acceleration a. R Exp(d) x ~ R x - R [x]x d, so with
  // dth_{k+1} from above:
  //   d a / d dth_k = -(R_k [a0]x + R_k1 [a1]x dR^T) / 2
  //   d a / d b_g   = -R_k1 [a1]x (d dth_{k+1} / d b_g) / 2
  //   d a / d b_a   = -(R_k + R_k1) / 2
  //   d a / d n_a0  = R_k / 2,  d a / d n_a1 = R_k1 / 2
  //   d a / d n_g   = -R_k1 [a1]x (Jr dt / 2) / 2   (both ends).
  const Eigen::Matrix3d R_k1_a1x = R_k1 * Skew(a1);
  const Eigen::Matrix3d d_a_d_th = -0.5 * (R_k * Skew(a0) + R_k1_a1x * dR_T);
  const Eigen::Matrix3d d_a_d_bg = -0.5 * R_k1_a1x * d_th1_d_bg;
  const Eigen::Matrix3d d_a_d_ba = -0.5 * (R_k + R_k1);
  const Eigen::Matrix3d d_a_d_ng = -0.25 * R_k1_a1x * Jr_dt;

  // p_{k+1} = p_k + v_k dt + a dt^2 / 2 and v_{k+1} = v_k + a dt pass every
  // derivative of a through the factors dt^2 / 2 and dt. E.g. the note's
  //   f15 = dt^2/2 * d a / d b_g = R_k1 [a1]x Jr dt^3 / 4,
  //   g12 = dt^2/2 * d a / d n_g0 = -R_k1 [a1]x Jr dt^3 / 8.
  const double h = 0.5 * dt * dt;
  if (d_next_d_curr != nullptr) {
    Matrix15d& F = *d_next_d_curr;
    F.setIdentity();
    F.block<3, 3>(kImuP, kImuR) = h * d_a_d_th;
    F.block<3, 3>(kImuP, kImuV) = Eigen::Matrix3d::Identity() * dt;
    F.block<3, 3>(kImuP, kImuBa) = h * d_a_d_ba;
    F.block<3, 3>(kImuP, kImuBg) = h * d_a_d_bg;
    F.block<3, 3>(kImuR, kImuR) = d_th1_d_th0;
    F.block<3, 3>(kImuR, kImuBg) = d_th1_d_bg;
    F.block<3, 3>(kImuV, kImuR) = dt * d_a_d_th;
    F.block<3, 3>(kImuV, kImuBa) = dt * d_a_d_ba;
    F.block<3, 3>(kImuV, kImuBg) = dt * d_a_d_bg;
  }
  if (d_next_d_noise != nullptr) {
    Matrix15x18d& G = *d_next_d_noise;
    G.setZero();
    G.block<3, 3>(kImuP, kNoiseAcc0) = h * 0.5 * R_k;
    G.block<3, 3>(kImuP, kNoiseAcc1) = h * 0.5 * R_k1;
    G.block<3, 3>(kImuP, kNoiseGyr0) = h * d_a_d_ng;
    G.block<3, 3>(kImuP, kNoiseGyr1) = h * d_a_d_ng;
    G.block<3, 3>(kImuR, kNoiseGyr0) = 0.5 * Jr_dt;
    G.block<3, 3>(kImuR, kNoiseGyr1) = 0.5 * Jr_dt;
    G.block<3, 3>(kImuV, kNoiseAcc0) = dt * 0.5 * R_k;
    G.block<3, 3>(kImuV, kNoiseAcc1) = dt * 0.5 * R_k1;
    G.block<3, 3>(kImuV, kNoiseGyr0) = dt * d_a_d_ng;
    G.block<3, 3>(kImuV, kNoiseGyr1) = dt * d_a_d_ng;
    G.block<3, 3>(kImuBa, kNoiseBa).setIdentity();
    G.block<3, 3>(kImuBg, kNoiseBg).setIdentity();
  }
  return next;
}

Eigen::Matrix<double, 18, 1> StepNoiseVariances(const ImuNoise& noise,
                                                double dt) {
  // A real sensor's sample k carries white noise of variance sigma^2 / T
  // (T the sample period), and sample k is an endpoint of two steps. Summed
  // over an interval the midpoint average (n_k + n_{k+1}) / 2 therefore
  // behaves like one noise of variance sigma^2 / dt per step, the
  // continuous-time value. Treating the two endpoint noises as independent
  // with sigma^2 / dt each (VINS-Mono) gives the average only half of that
  // and underestimates the white-noise covariance by a factor 2; giving each
  // 2 sigma^2 / dt restores it (checked by the Monte-Carlo test, which draws
  // noise per sample).
  const double acc_white = 2.0 * noise.accelerometer_noise_density *
                           noise.accelerometer_noise_density / dt;
  const double gyr_white =
      2.0 * noise.gyroscope_noise_density * noise.gyroscope_noise_density / dt;
  const double acc_walk =
      noise.accelerometer_random_walk * noise.accelerometer_random_walk * dt;
  const double gyr_walk =
      noise.gyroscope_random_walk * noise.gyroscope_random_walk * dt;
  Eigen::Matrix<double, 18, 1> q;
  q.segment<3>(kNoiseAcc0).setConstant(acc_white);
  q.segment<3>(kNoiseGyr0).setConstant(gyr_white);
  q.segment<3>(kNoiseAcc1).setConstant(acc_white);
  q.segment<3>(kNoiseGyr1).setConstant(gyr_white);
  q.segment<3>(kNoiseBa).setConstant(acc_walk);
  q.segment<3>(kNoiseBg).setConstant(gyr_walk);
  return q;
}

}  // namespace vio
