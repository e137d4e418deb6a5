#include "preintegration/midpoint_step.h"

#include <string>

#include "geometry/so3.h"

namespace vio {

namespace {

// The derivatives of one step's rotation and mean acceleration that F and G
// are assembled from.
struct StepPartials {
  double dt;
  Eigen::Matrix3d R_k, R_k1;    // rotations at both ends
  Eigen::Matrix3d d_th1_d_th0;  // d dth_{k+1} / d dth_k
  Eigen::Matrix3d Jr_dt;        // Jr(w dt) dt
  Eigen::Matrix3d d_a_d_th, d_a_d_ba, d_a_d_bg, d_a_d_ng;  // of the mean a
};

StepPartials Partials(const Eigen::Matrix3d& R_k, const Eigen::Matrix3d& R_k1,
                      const Eigen::Quaterniond& dq, const Eigen::Vector3d& phi,
                      const Eigen::Vector3d& a0, const Eigen::Vector3d& a1,
                      double dt) {
  StepPartials d;
  d.dt = dt;
  d.R_k = R_k;
  d.R_k1 = R_k1;
  // Rotation. R_k Exp(dth) Exp(phi) = R_k Exp(phi) Exp(dR^T dth), so
  //   dth_{k+1} = dR^T dth_k.
  // A gyro change e (bias -e, or noise e/2 at either end) moves phi by e dt
  // and Exp(phi + e dt) ~ Exp(phi) Exp(Jr(phi) e dt), so
  //   d dth_{k+1} / d b_g = -Jr dt,   d dth_{k+1} / d n_g0,1 = Jr dt / 2.
  const Eigen::Matrix3d dR_T = dq.toRotationMatrix().transpose();
  d.d_th1_d_th0 = dR_T;
  d.Jr_dt = RightJacobian(phi) * dt;
  // Mean acceleration a. R Exp(d) x ~ R x - R [x]x d, so with
  // dth_{k+1} from above:
  //   d a / d dth_k = -(R_k [a0]x + R_k1 [a1]x dR^T) / 2
  //   d a / d b_g   = -R_k1 [a1]x (d dth_{k+1} / d b_g) / 2
  //   d a / d b_a   = -(R_k + R_k1) / 2
  //   d a / d n_a0  = R_k / 2,  d a / d n_a1 = R_k1 / 2
  //   d a / d n_g   = -R_k1 [a1]x (Jr dt / 2) / 2   (both ends).
  const Eigen::Matrix3d R_k1_a1x = R_k1 * Skew(a1);
  d.d_a_d_th = -0.5 * (R_k * Skew(a0) + R_k1_a1x * dR_T);
  d.d_a_d_bg = 0.5 * R_k1_a1x * d.Jr_dt;
  d.d_a_d_ba = -0.5 * (R_k + R_k1);
  d.d_a_d_ng = -0.25 * R_k1_a1x * d.Jr_dt;
  return d;
}

// p_{k+1} = p_k + v_k dt + a dt^2 / 2 and v_{k+1} = v_k + a dt pass every
// derivative of a through the factors dt^2 / 2 and dt. E.g. the note's
//   f15 = dt^2/2 * d a / d b_g  = R_k1 [a1]x Jr dt^3 / 4,
//   g12 = dt^2/2 * d a / d n_g0 = -R_k1 [a1]x Jr dt^3 / 8.
void FillTransition(const StepPartials& d, Matrix15d* F) {
  const double h = 0.5 * d.dt * d.dt;
  F->setIdentity();
  F->block<3, 3>(kImuP, kImuR) = h * d.d_a_d_th;
  F->block<3, 3>(kImuP, kImuV) = Eigen::Matrix3d::Identity() * d.dt;
  F->block<3, 3>(kImuP, kImuBa) = h * d.d_a_d_ba;
  F->block<3, 3>(kImuP, kImuBg) = h * d.d_a_d_bg;
  F->block<3, 3>(kImuR, kImuR) = d.d_th1_d_th0;
  F->block<3, 3>(kImuR, kImuBg) = -d.Jr_dt;
  F->block<3, 3>(kImuV, kImuR) = d.dt * d.d_a_d_th;
  F->block<3, 3>(kImuV, kImuBa) = d.dt * d.d_a_d_ba;
  F->block<3, 3>(kImuV, kImuBg) = d.dt * d.d_a_d_bg;
}

void FillNoiseInput(const StepPartials& d, Matrix15x18d* G) {
  const double h = 0.5 * d.dt * d.dt;
  G->setZero();
  G->block<3, 3>(kImuP, kNoiseAcc0) = h * 0.5 * d.R_k;
  G->block<3, 3>(kImuP, kNoiseAcc1) = h * 0.5 * d.R_k1;
  G->block<3, 3>(kImuP, kNoiseGyr0) = h * d.d_a_d_ng;
  G->block<3, 3>(kImuP, kNoiseGyr1) = h * d.d_a_d_ng;
  G->block<3, 3>(kImuR, kNoiseGyr0) = 0.5 * d.Jr_dt;
  G->block<3, 3>(kImuR, kNoiseGyr1) = 0.5 * d.Jr_dt;
  G->block<3, 3>(kImuV, kNoiseAcc0) = d.dt * 0.5 * d.R_k;
  G->block<3, 3>(kImuV, kNoiseAcc1) = d.dt * 0.5 * d.R_k1;
  G->block<3, 3>(kImuV, kNoiseGyr0) = d.dt * d.d_a_d_ng;
  G->block<3, 3>(kImuV, kNoiseGyr1) = d.dt * d.d_a_d_ng;
  // b_{k+1} = b_k + n_b.
  G->block<3, 3>(kImuBa, kNoiseBa).setIdentity();
  G->block<3, 3>(kImuBg, kNoiseBg).setIdentity();
}

}  // namespace

ImuDelta MidpointStep(const ImuDelta& curr, const ImuSample& s0,
                      const ImuSample& s1, const Eigen::Vector3d& b_a,
                      const Eigen::Vector3d& b_g, Matrix15d* d_next_d_curr,
                      Matrix15x18d* d_next_d_noise) {
  if (s1.t_ns <= s0.t_ns) {
    throw ImuError("midpoint step from t = " + std::to_string(s0.t_ns) +
                   " ns to t = " + std::to_string(s1.t_ns) +
                   " ns: the second sample must come later");
  }
  const double dt = 1e-9 * static_cast<double>(s1.t_ns - s0.t_ns);
  const Eigen::Vector3d phi = (0.5 * (s0.gyr + s1.gyr) - b_g) * dt;
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
  const StepPartials d = Partials(R_k, R_k1, dq, phi, a0, a1, dt);
  if (d_next_d_curr != nullptr) FillTransition(d, d_next_d_curr);
  if (d_next_d_noise != nullptr) FillNoiseInput(d, d_next_d_noise);
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
