#ifndef VIO_TEST_TESTING_ANALYTIC_TRAJECTORY_H_
#define VIO_TEST_TESTING_ANALYTIC_TRAJECTORY_H_

// A smooth body trajectory known in closed form, and the noise-free IMU
// samples it produces: ground truth for preintegration and estimator tests
// (as Basalt's PredictTestGT and GTSAM's ScenarioRunner do).
//
//   p_w_b(t)  = sum of one sinusoid per axis:  A_i sin(w_i t + c_i)   [m]
//   q_w_b(t)  = Exp(phi(t)),  phi_i(t) = B_i sin(u_i t + d_i)         [rad]
//   omega_b   = Jr(phi) phi'(t)   (since d/dt Exp(phi) = Exp(phi) [Jr phi']x)
//   acc_b     = R_w_b^T (p''(t) - g_w) + b_a,   gyr_b = omega_b + b_g
// Time t [s] = t_ns * 1e-9; keep stamps within a few hours of 0 so that the
// conversion to double keeps sub-microsecond precision.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "preintegration/imu_types.h"

namespace vio {
namespace testing {

struct AnalyticTrajectoryParams {
  Eigen::Vector3d pos_amplitude{1.5, 1.2, 0.4};  // A [m]
  Eigen::Vector3d pos_frequency{1.3, 0.9, 1.7};  // w [rad/s]
  Eigen::Vector3d pos_phase{0.0, 0.5, 1.0};      // c [rad]
  Eigen::Vector3d rot_amplitude{0.4, 0.3, 1.2};  // B [rad]
  Eigen::Vector3d rot_frequency{1.1, 0.7, 0.5};  // u [rad/s]
  Eigen::Vector3d rot_phase{0.3, 0.0, 0.8};      // d [rad]
};

class AnalyticTrajectory {
 public:
  explicit AnalyticTrajectory(
      const AnalyticTrajectoryParams& params = AnalyticTrajectoryParams(),
      double gravity_magnitude = 9.81);

  // The n-th time derivative of p_w_b at t [s] (n = 0: position [m]).
  Eigen::Vector3d PositionDerivative(double t, int n) const;
  Eigen::Vector3d Position(double t) const { return PositionDerivative(t, 0); }
  Eigen::Vector3d Velocity(double t) const { return PositionDerivative(t, 1); }
  Eigen::Quaterniond Rotation(double t) const;      // q_w_b
  Eigen::Vector3d AngularVelocity(double t) const;  // omega_b [rad/s]

  // The noise-free sample at t_ns with the given biases added.
  ImuSample Sample(int64_t t_ns, const Eigen::Vector3d& b_a,
                   const Eigen::Vector3d& b_g) const;
  // Samples every period_ns from first_ns up to and including the first
  // stamp at or after last_ns.
  std::vector<ImuSample> Samples(int64_t first_ns, int64_t last_ns,
                                 int64_t period_ns, const Eigen::Vector3d& b_a,
                                 const Eigen::Vector3d& b_g) const;

  const Eigen::Vector3d& g_w() const { return g_w_; }

 private:
  Eigen::Vector3d Phi(double t, int n) const;  // n-th derivative of phi

  AnalyticTrajectoryParams params_;
  Eigen::Vector3d g_w_;
};

}  // namespace testing
}  // namespace vio

#endif  // VIO_TEST_TESTING_ANALYTIC_TRAJECTORY_H_
