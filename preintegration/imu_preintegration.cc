#include "preintegration/imu_preintegration.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <utility>

#include "geometry/so3.h"

namespace vio {
namespace {

std::string Stamp(int64_t t_ns) { return std::to_string(t_ns) + " ns"; }

std::string Interval(int64_t t0_ns, int64_t t1_ns) {
  return "[" + std::to_string(t0_ns) + ", " + std::to_string(t1_ns) + "] ns";
}

void CheckBiases(const Eigen::Vector3d& b_a, const Eigen::Vector3d& b_g,
                 int64_t t0_ns, int64_t t1_ns) {
  if (!b_a.allFinite() || !b_g.allFinite()) {
    throw ImuError("biases for the IMU interval " + Interval(t0_ns, t1_ns) +
                   " are not finite");
  }
}

void CheckStream(const std::vector<ImuSample>& samples) {
  for (size_t i = 0; i < samples.size(); ++i) {
    const ImuSample& s = samples[i];
    if (!s.acc.allFinite() || !s.gyr.allFinite()) {
      std::ostringstream out;
      out << "IMU sample at t = " << Stamp(s.t_ns)
          << " is not finite (acc = " << s.acc.transpose()
          << ", gyr = " << s.gyr.transpose() << ")";
      throw ImuError(out.str());
    }
    if (i > 0 && s.t_ns <= samples[i - 1].t_ns) {
      throw ImuError("IMU sample at t = " + Stamp(s.t_ns) +
                     " does not come after the previous one (t = " +
                     Stamp(samples[i - 1].t_ns) + "): stamps must increase");
    }
  }
}

}  // namespace

ImuSample InterpolateImuSample(const ImuSample& a, const ImuSample& b,
                               int64_t t_ns) {
  if (t_ns == a.t_ns) return a;
  if (t_ns == b.t_ns) return b;
  const double s =
      static_cast<double>(t_ns - a.t_ns) / static_cast<double>(b.t_ns - a.t_ns);
  ImuSample out;
  out.t_ns = t_ns;
  out.acc = (1.0 - s) * a.acc + s * b.acc;
  out.gyr = (1.0 - s) * a.gyr + s * b.gyr;
  return out;
}

ImuDelta PreintegratedImu::Corrected(const Eigen::Vector3d& b_a,
                                     const Eigen::Vector3d& b_g) const {
  const Eigen::Vector3d db_a = b_a - lin_b_a;
  const Eigen::Vector3d db_g = b_g - lin_b_g;
  ImuDelta out;
  out.p = delta.p + d_dp_d_ba * db_a + d_dp_d_bg * db_g;
  out.v = delta.v + d_dv_d_ba * db_a + d_dv_d_bg * db_g;
  out.q = (delta.q * ExpQuaternion(d_dq_d_bg * db_g)).normalized();
  return out;
}

std::vector<ImuSample> SliceImuInterval(int64_t t0_ns, int64_t t1_ns,
                                        const std::vector<ImuSample>& samples,
                                        double max_sample_gap) {
  if (t1_ns <= t0_ns) {
    throw ImuError("IMU interval " + Interval(t0_ns, t1_ns) +
                   " is empty: its end must come after its start");
  }
  CheckStream(samples);
  if (samples.empty()) {
    throw ImuError("no IMU samples for the interval " + Interval(t0_ns, t1_ns));
  }
  if (samples.front().t_ns > t0_ns || samples.back().t_ns < t1_ns) {
    throw ImuError("IMU samples span " +
                   Interval(samples.front().t_ns, samples.back().t_ns) +
                   " and do not cover the interval " + Interval(t0_ns, t1_ns));
  }
  const auto by_stamp = [](const ImuSample& s, int64_t t) {
    return s.t_ns < t;
  };
  const auto stamp_before = [](int64_t t, const ImuSample& s) {
    return t < s.t_ns;
  };
  // lo: the last sample at or before t0; hi: the first at or after t1.
  const size_t lo = static_cast<size_t>(
      std::upper_bound(samples.begin(), samples.end(), t0_ns, stamp_before) -
      samples.begin() - 1);
  const size_t hi = static_cast<size_t>(
      std::lower_bound(samples.begin(), samples.end(), t1_ns, by_stamp) -
      samples.begin());
  for (size_t k = lo; k < hi; ++k) {
    const double gap =
        1e-9 * static_cast<double>(samples[k + 1].t_ns - samples[k].t_ns);
    if (gap > max_sample_gap) {
      throw ImuError("IMU gap of " + std::to_string(gap) +
                     " s between t = " + Stamp(samples[k].t_ns) + " and t = " +
                     Stamp(samples[k + 1].t_ns) + " exceeds max_sample_gap (" +
                     std::to_string(max_sample_gap) + " s)");
    }
  }
  std::vector<ImuSample> out;
  out.reserve(hi - lo + 1);
  out.push_back(InterpolateImuSample(samples[lo], samples[lo + 1], t0_ns));
  for (size_t k = lo + 1; k < hi; ++k) out.push_back(samples[k]);
  out.push_back(InterpolateImuSample(samples[hi - 1], samples[hi], t1_ns));
  return out;
}

ImuPreintegration::ImuPreintegration(int64_t t0_ns, int64_t t1_ns,
                                     const std::vector<ImuSample>& samples,
                                     const Eigen::Vector3d& b_a,
                                     const Eigen::Vector3d& b_g,
                                     const ImuNoise& noise,
                                     const PreintegrationOptions& options)
    : ImuPreintegration(
          SliceImuInterval(t0_ns, t1_ns, samples, options.max_sample_gap), b_a,
          b_g, noise, options) {}

ImuPreintegration::ImuPreintegration(std::vector<ImuSample> interval_samples,
                                     const Eigen::Vector3d& b_a,
                                     const Eigen::Vector3d& b_g,
                                     const ImuNoise& noise,
                                     const PreintegrationOptions& options)
    : samples_(std::move(interval_samples)), noise_(noise), options_(options) {
  std::string message;
  if (!noise_.Validate(&message)) throw ImuError("ImuNoise: " + message);
  if (!options_.Validate(&message)) {
    throw ImuError("PreintegrationOptions: " + message);
  }
  CheckBiases(b_a, b_g, samples_.front().t_ns, samples_.back().t_ns);
  result_.lin_b_a = b_a;
  result_.lin_b_g = b_g;
  Integrate();
}

void ImuPreintegration::Integrate() {
  result_.delta = ImuDelta();
  running_covariance_.setZero();
  // d x / d [b_a, b_g]. The biases are part of the error state and constant
  // through F's identity bias block, so to first order
  // x_N = F_{N-1} ... F_0 x_0 and the bias Jacobians are the bias columns of
  // that product, started from d x_0 / d b = [0; I].
  d_x_d_b_.setZero();
  d_x_d_b_.bottomRows<6>().setIdentity();
  Propagate(0);
}

void ImuPreintegration::Propagate(size_t from) {
  PreintegratedImu& r = result_;
  r.t0_ns = samples_.front().t_ns;
  r.t1_ns = samples_.back().t_ns;
  r.sum_dt = 1e-9 * static_cast<double>(r.t1_ns - r.t0_ns);
  Matrix15d F;
  Matrix15x18d G;
  for (size_t k = from; k + 1 < samples_.size(); ++k) {
    const double dt =
        1e-9 * static_cast<double>(samples_[k + 1].t_ns - samples_[k].t_ns);
    r.delta = MidpointStep(r.delta, samples_[k], samples_[k + 1], r.lin_b_a,
                           r.lin_b_g, &F, &G);
    running_covariance_ =
        F * running_covariance_ * F.transpose() +
        G * StepNoiseVariances(noise_, dt).asDiagonal() * G.transpose();
    d_x_d_b_ = F * d_x_d_b_;
  }
  // Symmetric up to rounding; make it exactly so for the Cholesky factor.
  r.covariance = 0.5 * (running_covariance_ + running_covariance_.transpose());
  r.d_dp_d_ba = d_x_d_b_.block<3, 3>(kImuP, 0);
  r.d_dp_d_bg = d_x_d_b_.block<3, 3>(kImuP, 3);
  r.d_dq_d_bg = d_x_d_b_.block<3, 3>(kImuR, 3);
  r.d_dv_d_ba = d_x_d_b_.block<3, 3>(kImuV, 0);
  r.d_dv_d_bg = d_x_d_b_.block<3, 3>(kImuV, 3);
}

ImuPreintegration ImuPreintegration::Merge(const ImuPreintegration& first,
                                           const ImuPreintegration& second) {
  if (first.t1_ns() != second.t0_ns()) {
    throw ImuError("cannot merge IMU intervals " +
                   Interval(first.t0_ns(), first.t1_ns()) + " and " +
                   Interval(second.t0_ns(), second.t1_ns()) +
                   ": the first must end where the second starts");
  }
  // Both hold the sample at the shared stamp; keep first's, and go on from
  // it with first's running state.
  ImuPreintegration merged(first);
  const size_t from = merged.samples_.size() - 1;
  merged.samples_.insert(merged.samples_.end(), second.samples_.begin() + 1,
                         second.samples_.end());
  merged.Propagate(from);
  return merged;
}

void ImuPreintegration::Repropagate(const Eigen::Vector3d& b_a,
                                    const Eigen::Vector3d& b_g) {
  CheckBiases(b_a, b_g, t0_ns(), t1_ns());
  result_.lin_b_a = b_a;
  result_.lin_b_g = b_g;
  Integrate();
}

bool ImuPreintegration::NeedsRepropagation(const Eigen::Vector3d& b_a,
                                           const Eigen::Vector3d& b_g) const {
  return (b_a - lin_b_a()).norm() > options_.repropagate_acc_bias_change ||
         (b_g - lin_b_g()).norm() > options_.repropagate_gyr_bias_change;
}

bool ImuPreintegration::UpdateBiasEstimate(const Eigen::Vector3d& b_a,
                                           const Eigen::Vector3d& b_g) {
  CheckBiases(b_a, b_g, t0_ns(), t1_ns());
  if (!NeedsRepropagation(b_a, b_g)) return false;
  Repropagate(b_a, b_g);
  return true;
}

}  // namespace vio
