#ifndef VIO_PREINTEGRATION_IMU_PREINTEGRATION_H_
#define VIO_PREINTEGRATION_IMU_PREINTEGRATION_H_

// IMU preintegration between two keyframe stamps t0_ns < t1_ns.
//
// The samples of the interval are integrated with the midpoint scheme of
// midpoint_step.h; at the two ends the samples are linearly interpolated to
// the exact stamps. Along with delta_p, delta_v, delta_q (in the body frame at
// t0) it propagates
//   - the 15 x 15 covariance of the error state [dp, dtheta, dv, db_a, db_g]
//     (P <- F P F^T + G Q G^T, Q from ImuNoise per step), which is the
//     covariance of the IMU residual (DESIGN.md order);
//   - the Jacobians of delta_p, delta_v, delta_q with respect to the biases at
//     the linearisation biases (J <- F J), for the first-order correction
//       delta_p(b) ~ delta_p + d_dp_d_ba db_a + d_dp_d_bg db_g
//       delta_v(b) ~ delta_v + d_dv_d_ba db_a + d_dv_d_bg db_g
//       delta_q(b) ~ delta_q (x) Exp(d_dq_d_bg db_g)
//     with db = b - linearisation bias (Forster et al., T-RO 2017, sec. V-C).
// The samples are kept, so the interval can be re-integrated with new
// linearisation biases or merged with the next interval.
//
// Bad input is rejected with vio::ImuError (an std::invalid_argument) whose
// message names the stamp: non-increasing stamps, a non-finite sample, a gap
// between consecutive samples of the interval longer than
// PreintegrationOptions::max_sample_gap, an interval not covered by samples
// (t1 <= t0 included). Invalid ImuNoise or options are ImuErrors too.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "preintegration/imu_types.h"
#include "preintegration/midpoint_step.h"

namespace vio {

// What an interval's preintegration yields: a plain value that the IMU factor
// copies, so the factor does not depend on the preintegration's lifetime.
struct PreintegratedImu {
  int64_t t0_ns = 0;                         // interval start [ns]
  int64_t t1_ns = 0;                         // interval end [ns]
  double sum_dt = 0.0;                       // t1 - t0 [s]
  ImuDelta delta;                            // at the linearisation biases
  Matrix15d covariance = Matrix15d::Zero();  // [dp, dth, dv, db_a, db_g]
  // Bias Jacobians at the linearisation biases (delta_q's on the right
  // tangent; d delta_q / d b_a is zero).
  Eigen::Matrix3d d_dp_d_ba = Eigen::Matrix3d::Zero();  // [s^2]
  Eigen::Matrix3d d_dp_d_bg = Eigen::Matrix3d::Zero();  // [m s]
  Eigen::Matrix3d d_dq_d_bg = Eigen::Matrix3d::Zero();  // [s]
  Eigen::Matrix3d d_dv_d_ba = Eigen::Matrix3d::Zero();  // [s]
  Eigen::Matrix3d d_dv_d_bg = Eigen::Matrix3d::Zero();  // [m]
  Eigen::Vector3d lin_b_a = Eigen::Vector3d::Zero();    // [m/s^2]
  Eigen::Vector3d lin_b_g = Eigen::Vector3d::Zero();    // [rad/s]

  // The first-order bias-corrected terms for biases b_a, b_g.
  ImuDelta Corrected(const Eigen::Vector3d& b_a,
                     const Eigen::Vector3d& b_g) const;
};

class ImuPreintegration {
 public:
  // Integrates the samples covering [t0_ns, t1_ns] with linearisation biases
  // b_a [m/s^2] and b_g [rad/s]. `samples` may be a longer stream (e.g. the
  // estimator's whole buffer): it must be strictly increasing and finite
  // throughout, and it must hold a sample at or before t0_ns and one at or
  // after t1_ns. Throws ImuError otherwise (see the file comment).
  ImuPreintegration(int64_t t0_ns, int64_t t1_ns,
                    const std::vector<ImuSample>& samples,
                    const Eigen::Vector3d& b_a, const Eigen::Vector3d& b_g,
                    const ImuNoise& noise,
                    const PreintegrationOptions& options);

  // The preintegration of [first.t0, second.t1] over both intervals' samples
  // with first's linearisation biases, noise and options (for dropping the
  // keyframe between them). It continues first's integration through
  // second's samples instead of starting again from t0, so a keyframe
  // interval that keeps absorbing frames costs its new samples only; the
  // result is bit for bit that of integrating the joined samples from the
  // start (Repropagate with the same biases). Throws ImuError unless
  // first.t1_ns() == second.t0_ns().
  static ImuPreintegration Merge(const ImuPreintegration& first,
                                 const ImuPreintegration& second);

  // Re-integrates the stored samples with new linearisation biases.
  void Repropagate(const Eigen::Vector3d& b_a, const Eigen::Vector3d& b_g);

  // True when b_a or b_g leaves the linearisation biases by more than the
  // options' thresholds, i.e. when the first-order correction should not be
  // trusted any more.
  bool NeedsRepropagation(const Eigen::Vector3d& b_a,
                          const Eigen::Vector3d& b_g) const;

  // For a new bias estimate: re-integrates when NeedsRepropagation, otherwise
  // keeps the linearisation (callers use Corrected). Returns whether it
  // re-integrated.
  bool UpdateBiasEstimate(const Eigen::Vector3d& b_a,
                          const Eigen::Vector3d& b_g);

  // The first-order bias-corrected terms (PreintegratedImu::Corrected).
  ImuDelta Corrected(const Eigen::Vector3d& b_a,
                     const Eigen::Vector3d& b_g) const {
    return result_.Corrected(b_a, b_g);
  }

  const PreintegratedImu& result() const { return result_; }
  int64_t t0_ns() const { return result_.t0_ns; }
  int64_t t1_ns() const { return result_.t1_ns; }
  double sum_dt() const { return result_.sum_dt; }
  const ImuDelta& delta() const { return result_.delta; }
  const Matrix15d& covariance() const { return result_.covariance; }
  const Eigen::Vector3d& lin_b_a() const { return result_.lin_b_a; }
  const Eigen::Vector3d& lin_b_g() const { return result_.lin_b_g; }
  // The integrated samples: the interpolated one at t0, those strictly
  // inside, the interpolated one at t1.
  const std::vector<ImuSample>& samples() const { return samples_; }
  const ImuNoise& noise() const { return noise_; }
  const PreintegrationOptions& options() const { return options_; }

 private:
  ImuPreintegration(std::vector<ImuSample> interval_samples,
                    const Eigen::Vector3d& b_a, const Eigen::Vector3d& b_g,
                    const ImuNoise& noise,
                    const PreintegrationOptions& options);

  // Integrate: from the first sample; Propagate: continues the running
  // state below from samples_[from] to the end and refreshes result_.
  void Integrate();
  void Propagate(size_t from);

  std::vector<ImuSample> samples_;
  ImuNoise noise_;
  PreintegrationOptions options_;
  PreintegratedImu result_;
  // The running state Propagate continues from: the covariance before the
  // final symmetrisation and d x / d [b_a, b_g] (result_ keeps its blocks).
  Matrix15d running_covariance_ = Matrix15d::Zero();
  Eigen::Matrix<double, 15, 6> d_x_d_b_ = Eigen::Matrix<double, 15, 6>::Zero();
};

// The samples of [t0_ns, t1_ns] with interpolated ends, after checking the
// stream and the interval (the ImuPreintegration constructor's checks).
// Exposed for tests and for callers that want to check a stream early.
std::vector<ImuSample> SliceImuInterval(int64_t t0_ns, int64_t t1_ns,
                                        const std::vector<ImuSample>& samples,
                                        double max_sample_gap);

// Linear interpolation between samples a and b at t_ns (a.t_ns <= t_ns <=
// b.t_ns): the ends SliceImuInterval makes; a or b itself at their stamps.
ImuSample InterpolateImuSample(const ImuSample& a, const ImuSample& b,
                               int64_t t_ns);

}  // namespace vio

#endif  // VIO_PREINTEGRATION_IMU_PREINTEGRATION_H_
