#include "preintegration/gyro_rotation.h"

#include <algorithm>
#include <string>

#include "geometry/so3.h"
#include "preintegration/imu_preintegration.h"

namespace vio {
namespace {

struct RotationState {
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  Eigen::Matrix3d J = Eigen::Matrix3d::Zero();  // d dq / d b_g
};

// One midpoint step of the rotation and its bias Jacobian (the header's
// recursion; the same expressions as MidpointStep and its F).
void Step(const ImuSample& s0, const ImuSample& s1, const Eigen::Vector3d& b_g,
          RotationState* state) {
  const double dt = 1e-9 * static_cast<double>(s1.t_ns - s0.t_ns);
  const Eigen::Vector3d phi = (0.5 * (s0.gyr + s1.gyr) - b_g) * dt;
  const Eigen::Quaterniond dq = ExpQuaternion(phi);
  const Eigen::Matrix3d dR_T = dq.toRotationMatrix().transpose();
  const Eigen::Matrix3d Jr_dt = RightJacobian(phi) * dt;
  state->q = (state->q * dq).normalized();
  // R Exp(dth) Exp(phi + e dt) ~ R Exp(phi) Exp(dR^T dth - Jr dt db_g).
  state->J = dR_T * state->J - Jr_dt;
}

}  // namespace

Eigen::Quaterniond GyroRotation::Corrected(const Eigen::Vector3d& b_g) const {
  return (delta_q * ExpQuaternion(d_dq_d_bg * (b_g - lin_b_g))).normalized();
}

std::vector<GyroRotation> IntegrateGyroRotations(
    int64_t t0_ns, const std::vector<int64_t>& t1_ns,
    const std::vector<ImuSample>& samples, const Eigen::Vector3d& b_g,
    double max_sample_gap) {
  if (t1_ns.empty()) return {};
  if (!b_g.allFinite()) {
    throw ImuError("gyroscope bias for the rotations from t = " +
                   std::to_string(t0_ns) + " ns is not finite");
  }
  for (size_t k = 0; k < t1_ns.size(); ++k) {
    // After the start; equal consecutive end stamps give equal rotations.
    const bool ordered = k == 0 ? t1_ns[k] > t0_ns : t1_ns[k] >= t1_ns[k - 1];
    if (!ordered) {
      throw ImuError("rotation end stamp " + std::to_string(t1_ns[k]) +
                     " ns comes before " +
                     std::to_string(k == 0 ? t0_ns : t1_ns[k - 1]) +
                     " ns: end stamps must follow the start, in order");
    }
  }
  // The checks of the whole span; its inner samples are those of every
  // end stamp's interval.
  const std::vector<ImuSample> span =
      SliceImuInterval(t0_ns, t1_ns.back(), samples, max_sample_gap);
  const auto by_stamp = [](const ImuSample& s, int64_t t) {
    return s.t_ns < t;
  };
  std::vector<GyroRotation> out;
  out.reserve(t1_ns.size());
  RotationState running;
  size_t i = 0;  // running is at span[i]
  for (const int64_t t : t1_ns) {
    // The inner samples before t (span's last element is the interpolated
    // end, not an inner sample).
    while (i + 2 < span.size() && span[i + 1].t_ns < t) {
      Step(span[i], span[i + 1], b_g, &running);
      ++i;
    }
    // The end sample interpolated between the stream's samples around t,
    // as SliceImuInterval makes it for [t0_ns, t].
    const size_t hi = static_cast<size_t>(
        std::lower_bound(samples.begin(), samples.end(), t, by_stamp) -
        samples.begin());
    const ImuSample end = InterpolateImuSample(samples[hi - 1], samples[hi], t);
    RotationState closed = running;
    Step(span[i], end, b_g, &closed);
    GyroRotation r;
    r.t0_ns = t0_ns;
    r.t1_ns = t;
    r.delta_q = closed.q;
    r.d_dq_d_bg = closed.J;
    r.lin_b_g = b_g;
    out.push_back(r);
  }
  return out;
}

}  // namespace vio
