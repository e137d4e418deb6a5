#include "test/testing/analytic_trajectory.h"

#include <cmath>

#include "geometry/so3.h"

namespace vio {
namespace testing {
namespace {

// n-th derivative of a_i sin(f_i t + c_i), per axis:
// a_i f_i^n sin(f_i t + c_i + n pi / 2).
Eigen::Vector3d SineDerivative(const Eigen::Vector3d& a,
                               const Eigen::Vector3d& f,
                               const Eigen::Vector3d& c, double t, int n) {
  Eigen::Vector3d out;
  for (int i = 0; i < 3; ++i) {
    out[i] = a[i] * std::pow(f[i], n) * std::sin(f[i] * t + c[i] + n * M_PI_2);
  }
  return out;
}

}  // namespace

AnalyticTrajectory::AnalyticTrajectory(const AnalyticTrajectoryParams& params,
                                       double gravity_magnitude)
    : params_(params), g_w_(0.0, 0.0, -gravity_magnitude) {}

Eigen::Vector3d AnalyticTrajectory::PositionDerivative(double t, int n) const {
  return SineDerivative(params_.pos_amplitude, params_.pos_frequency,
                        params_.pos_phase, t, n);
}

Eigen::Vector3d AnalyticTrajectory::Phi(double t, int n) const {
  return SineDerivative(params_.rot_amplitude, params_.rot_frequency,
                        params_.rot_phase, t, n);
}

Eigen::Quaterniond AnalyticTrajectory::Rotation(double t) const {
  return ExpQuaternion(Phi(t, 0));
}

Eigen::Vector3d AnalyticTrajectory::AngularVelocity(double t) const {
  return RightJacobian(Phi(t, 0)) * Phi(t, 1);
}

ImuSample AnalyticTrajectory::Sample(int64_t t_ns, const Eigen::Vector3d& b_a,
                                     const Eigen::Vector3d& b_g) const {
  const double t = 1e-9 * static_cast<double>(t_ns);
  ImuSample s;
  s.t_ns = t_ns;
  s.acc = Rotation(t).conjugate() * (PositionDerivative(t, 2) - g_w_) + b_a;
  s.gyr = AngularVelocity(t) + b_g;
  return s;
}

std::vector<ImuSample> AnalyticTrajectory::Samples(
    int64_t first_ns, int64_t last_ns, int64_t period_ns,
    const Eigen::Vector3d& b_a, const Eigen::Vector3d& b_g) const {
  std::vector<ImuSample> out;
  for (int64_t t = first_ns; out.empty() || out.back().t_ns < last_ns;
       t += period_ns) {
    out.push_back(Sample(t, b_a, b_g));
  }
  return out;
}

}  // namespace testing
}  // namespace vio
