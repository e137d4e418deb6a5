#include "dataset/imu_curve_residual.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>

namespace vio {
namespace {

using Series = std::vector<Eigen::Vector3d>;

struct Residuals {
  Series gyr;
  Series acc;
};

// r_g and r_a of every sample at offset d (header).
Residuals ResidualsAt(const TrajectoryCurve& curve,
                      const std::vector<ImuSample>& samples, double d,
                      double gravity) {
  Residuals r;
  r.gyr.reserve(samples.size());
  r.acc.reserve(samples.size());
  const Eigen::Vector3d g_w(0.0, 0.0, -gravity);
  for (const ImuSample& s : samples) {
    const double t =
        static_cast<double>(s.t_ns - curve.start_ns()) * 1e-9 + d;
    const SimState x = curve.At(t);
    r.gyr.push_back(s.gyr - x.w_b);
    r.acc.push_back(s.acc - x.q_w_b.conjugate() * (x.a_w - g_w));
  }
  return r;
}

// Prefix sums: sums[k] = sum of x[0..k-1].
Series PrefixSums(const Series& x) {
  Series sums(x.size() + 1, Eigen::Vector3d::Zero());
  for (std::size_t k = 0; k < x.size(); ++k) sums[k + 1] = sums[k] + x[k];
  return sums;
}

// Rms per axis of x minus its centred moving average over `window` samples
// (shortened at the ends).
Eigen::Vector3d DetrendedRms(const Series& x, int window) {
  const Series sums = PrefixSums(x);
  const int n = static_cast<int>(x.size());
  const int half = std::max(window / 2, 1);
  Eigen::Vector3d sq = Eigen::Vector3d::Zero();
  for (int k = 0; k < n; ++k) {
    const int a = std::max(k - half, 0);
    const int b = std::min(k + half + 1, n);
    const Eigen::Vector3d mean = (sums[b] - sums[a]) / (b - a);
    sq += (x[k] - mean).cwiseAbs2();
  }
  return (sq / n).cwiseSqrt();
}

// Overlapping Allan deviation per axis at m samples per cluster:
//   adev^2 = 1 / (2 (N - 2m + 1)) sum_k (ybar_{k+m} - ybar_k)^2,
// ybar_k the mean of x[k..k+m-1]. Zero when fewer than 2m samples.
Eigen::Vector3d AllanDeviation(const Series& sums, int m) {
  const int n = static_cast<int>(sums.size()) - 1;
  if (m < 1 || 2 * m > n) return Eigen::Vector3d::Zero();
  Eigen::Vector3d sq = Eigen::Vector3d::Zero();
  const int count = n - 2 * m + 1;
  for (int k = 0; k < count; ++k) {
    const Eigen::Vector3d first = (sums[k + m] - sums[k]) / m;
    const Eigen::Vector3d second = (sums[k + 2 * m] - sums[k + m]) / m;
    sq += (second - first).cwiseAbs2();
  }
  return (sq / (2.0 * count)).cwiseSqrt();
}

double Norm2(const Eigen::Vector3d& rms) { return rms.squaredNorm(); }

// The offset in [lo, hi] on a grid of `step` that minimises the detrended
// rms of the gyroscope (gyro = true) or accelerometer residual.
double BestOffset(const TrajectoryCurve& curve,
                  const std::vector<ImuSample>& samples, double lo, double hi,
                  double step, bool gyro, int window, double gravity) {
  double best_d = lo;
  double best = INFINITY;
  const int steps = static_cast<int>(std::floor((hi - lo) / step + 0.5));
  for (int i = 0; i <= steps; ++i) {
    const double d = lo + i * step;
    const Residuals r = ResidualsAt(curve, samples, d, gravity);
    const double cost = Norm2(DetrendedRms(gyro ? r.gyr : r.acc, window));
    if (cost < best) {
      best = cost;
      best_d = d;
    }
  }
  return best_d;
}

}  // namespace

ImuCurveResidual CompareImuWithCurve(const TrajectoryCurve& curve,
                                     const std::vector<ImuSample>& imu,
                                     const ImuCurveResidualOptions& options) {
  if (!(options.gravity_m_s2 > 0.0) || !(options.max_offset_s > 0.0) ||
      !(options.coarse_step_s > 0.0) || !(options.fine_step_s > 0.0) ||
      !(options.bias_window_s > 0.0)) {
    throw std::invalid_argument(
        "imu curve residual: gravity, offsets, steps and window must be > 0");
  }
  const auto margin_ns =
      static_cast<int64_t>(std::ceil(options.max_offset_s * 1e9));
  std::vector<ImuSample> samples;
  for (const ImuSample& s : imu) {
    if (s.t_ns >= curve.start_ns() + margin_ns &&
        s.t_ns <= curve.end_ns() - margin_ns) {
      samples.push_back(s);
    }
  }
  if (samples.size() < 100) {
    throw std::invalid_argument(
        "imu curve residual: fewer than 100 IMU samples inside the curve's "
        "span");
  }
  ImuCurveResidual out;
  out.samples = static_cast<int>(samples.size());
  out.sample_rate_hz =
      (out.samples - 1) /
      (static_cast<double>(samples.back().t_ns - samples.front().t_ns) * 1e-9);
  const int window = std::max(
      static_cast<int>(std::lround(options.bias_window_s * out.sample_rate_hz)),
      1);
  const double g = options.gravity_m_s2;
  const double m = options.max_offset_s;
  for (const bool gyro : {true, false}) {
    const double coarse = BestOffset(curve, samples, -m, m,
                                     options.coarse_step_s, gyro, window, g);
    const double lo = std::max(coarse - options.coarse_step_s, -m);
    const double hi = std::min(coarse + options.coarse_step_s, m);
    const double fine =
        BestOffset(curve, samples, lo, hi, options.fine_step_s, gyro, window, g);
    (gyro ? out.gyr_offset_s : out.acc_offset_s) = fine;
  }
  const Residuals zero = ResidualsAt(curve, samples, 0.0, g);
  out.gyr_rms_at_zero = DetrendedRms(zero.gyr, window);
  out.acc_rms_at_zero = DetrendedRms(zero.acc, window);
  const Residuals best = ResidualsAt(curve, samples, out.gyr_offset_s, g);
  out.gyr_rms_at_best = DetrendedRms(best.gyr, window);
  out.acc_rms_at_best = DetrendedRms(best.acc, window);
  const Series gyr_sums = PrefixSums(best.gyr);
  const Series acc_sums = PrefixSums(best.acc);
  for (const double tau : options.allan_tau_s) {
    const int cluster =
        static_cast<int>(std::lround(tau * out.sample_rate_hz));
    if (cluster < 1 || 2 * cluster > out.samples) continue;
    AllanPoint p;
    p.tau_s = cluster / out.sample_rate_hz;
    p.gyr = AllanDeviation(gyr_sums, cluster);
    p.acc = AllanDeviation(acc_sums, cluster);
    out.allan.push_back(p);
  }
  return out;
}

}  // namespace vio
