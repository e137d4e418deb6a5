#include "navigation/pose_filter.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "navigation/kalman_filter.h"
#include "navigation/white_acceleration_model.h"

namespace vio {
namespace {

void RequirePositive(double value, const char* name) {
  if (!(value > 0.0) || !std::isfinite(value)) {
    throw std::invalid_argument(std::string("PoseFilterOptions: ") + name +
                                " must be finite and > 0 (got " +
                                std::to_string(value) + ")");
  }
}

double Seconds(int64_t dt_ns) { return 1e-9 * static_cast<double>(dt_ns); }

Eigen::Vector4d Sigmas(const PoseFilterOptions& o) {
  return {o.position_noise_m, o.position_noise_m, o.position_noise_m,
          o.yaw_noise_rad};
}

// H picks x, y, z and yaw out of the state.
Eigen::MatrixXd MeasurementMatrix() {
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(4, kFilterStateSize);
  H(0, kFilterX) = H(1, kFilterY) = H(2, kFilterZ) = H(3, kFilterYaw) = 1.0;
  return H;
}

}  // namespace

void PoseFilterOptions::Validate() const {
  RequirePositive(position_noise_m, "position_noise_m");
  RequirePositive(accel_noise_m_s2, "accel_noise_m_s2");
  RequirePositive(yaw_noise_rad, "yaw_noise_rad");
  RequirePositive(yaw_accel_noise_rad_s2, "yaw_accel_noise_rad_s2");
  RequirePositive(initial_speed_sigma_m_s, "initial_speed_sigma_m_s");
  RequirePositive(initial_yaw_rate_sigma_rad_s, "initial_yaw_rate_sigma_rad_s");
}

PoseFilter::PoseFilter(const PoseFilterOptions& options) : options_(options) {
  options_.Validate();
}

FilteredPose PoseFilter::Add(const PoseMeasurement& m) {
  if (!m.p_w.allFinite() || !std::isfinite(m.yaw_rad)) {
    throw std::invalid_argument("PoseFilter: non-finite measurement");
  }
  Eigen::Vector4d z(m.p_w.x(), m.p_w.y(), m.p_w.z(), WrapToPi(m.yaw_rad));
  const Eigen::Vector4d sigmas = Sigmas(options_);
  const Eigen::MatrixXd Q = sigmas.cwiseAbs2().asDiagonal();
  if (!started_) {
    started_ = true;
    t_ns_ = m.t_ns;
    mu_ = Eigen::VectorXd::Zero(kFilterStateSize);
    sigma_ = Eigen::MatrixXd::Zero(kFilterStateSize, kFilterStateSize);
    const double rate_sigma[4] = {options_.initial_speed_sigma_m_s,
                                  options_.initial_speed_sigma_m_s,
                                  options_.initial_speed_sigma_m_s,
                                  options_.initial_yaw_rate_sigma_rad_s};
    for (int axis = 0; axis < 4; ++axis) {
      mu_(2 * axis) = z(axis);
      sigma_(2 * axis, 2 * axis) = sigmas(axis) * sigmas(axis);
      sigma_(2 * axis + 1, 2 * axis + 1) = rate_sigma[axis] * rate_sigma[axis];
    }
    return Output(mu_, t_ns_, 0.0);
  }
  if (m.t_ns <= t_ns_) {
    throw std::invalid_argument("PoseFilter: stamp " + std::to_string(m.t_ns) +
                                " ns is not after the previous one (" +
                                std::to_string(t_ns_) + ")");
  }
  const double T = Seconds(m.t_ns - t_ns_);
  const double k = options_.accel_noise_m_s2;
  KalmanFilter filter(mu_, sigma_);
  filter.Predict(Transition(4, T),
                 ProcessNoise(T, {k, k, k, options_.yaw_accel_noise_rad_s2}));
  const KalmanUpdateInfo info =
      filter.Update(z, MeasurementMatrix(), Q, /*angle_rows=*/{3});
  mu_ = filter.mean();
  sigma_ = filter.covariance();
  mu_(kFilterYaw) = WrapToPi(mu_(kFilterYaw));
  t_ns_ = m.t_ns;
  return Output(mu_, t_ns_, info.nis);
}

FilteredPose PoseFilter::PredictAhead(double dt_s) const {
  if (!started_) throw std::logic_error("PoseFilter: PredictAhead before Add");
  const Eigen::VectorXd x = Transition(4, dt_s) * mu_;
  return Output(x, t_ns_ + std::llround(dt_s * 1e9), 0.0);
}

const Eigen::MatrixXd& PoseFilter::covariance() const { return sigma_; }

FilteredPose PoseFilter::Output(const Eigen::VectorXd& x, int64_t t_ns,
                                double nis) const {
  FilteredPose out;
  out.t_ns = t_ns;
  out.p_w = {x(kFilterX), x(kFilterY), x(kFilterZ)};
  out.v_w = {x(kFilterX + 1), x(kFilterY + 1), x(kFilterZ + 1)};
  out.yaw_rad = WrapToPi(x(kFilterYaw));
  out.yaw_rate_rad_s = x(kFilterYaw + 1);
  out.nis = nis;
  return out;
}

double YawOf(const Eigen::Quaterniond& q_w_b) {
  // Left-multiplying by Rz(d) = (cos d/2, 0, 0, sin d/2) turns the pair
  // (q.w, q.z) by d/2 and mixes q.x with q.y: the twist angle grows by d.
  const Eigen::Quaterniond q = q_w_b.normalized();
  return WrapToPi(2.0 * std::atan2(q.z(), q.w()));
}

Eigen::Quaterniond WithYaw(const Eigen::Quaterniond& q_w_b, double yaw_rad) {
  const Eigen::AngleAxisd change(yaw_rad - YawOf(q_w_b),
                                 Eigen::Vector3d::UnitZ());
  return (Eigen::Quaterniond(change) * q_w_b.normalized()).normalized();
}

}  // namespace vio
