#include "eval/metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

#include "geometry/so3.h"

namespace vio {
namespace {

constexpr double kRadToDeg = 180.0 / 3.14159265358979323846;

void CheckSameSize(const Trajectory& a, const Trajectory& b, const char* who) {
  if (a.size() != b.size()) {
    throw std::invalid_argument(std::string(who) +
                                ": the trajectories are not associated (" +
                                std::to_string(a.size()) + " vs " +
                                std::to_string(b.size()) + " poses)");
  }
}

// a^-1 b for poses (R, p): rotation R_a^T R_b, translation R_a^T (p_b - p_a).
struct Relative {
  Eigen::Quaterniond q;
  Eigen::Vector3d t;
};
Relative Between(const Eigen::Quaterniond& q_a, const Eigen::Vector3d& p_a,
                 const Eigen::Quaterniond& q_b, const Eigen::Vector3d& p_b) {
  const Eigen::Quaterniond q_a_inv = q_a.conjugate();
  return {q_a_inv * q_b, q_a_inv * (p_b - p_a)};
}

double AngleDeg(const Eigen::Quaterniond& q) {
  return Log(q).norm() * kRadToDeg;
}

}  // namespace

ErrorStats ComputeStats(const std::vector<double>& errors) {
  ErrorStats s;
  s.count = errors.size();
  if (errors.empty()) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    s.rmse = s.mean = s.median = s.std = s.min = s.max = nan;
    return s;
  }
  const double n = static_cast<double>(errors.size());
  double sum = 0.0, sum_sq = 0.0;
  for (double e : errors) {
    sum += e;
    sum_sq += e * e;
  }
  s.mean = sum / n;
  s.rmse = std::sqrt(sum_sq / n);
  double var = 0.0;
  for (double e : errors) var += (e - s.mean) * (e - s.mean);
  s.std = std::sqrt(var / n);
  std::vector<double> sorted = errors;
  std::sort(sorted.begin(), sorted.end());
  const size_t mid = sorted.size() / 2;
  s.median = sorted.size() % 2 == 1 ? sorted[mid]
                                    : 0.5 * (sorted[mid - 1] + sorted[mid]);
  s.min = sorted.front();
  s.max = sorted.back();
  return s;
}

AbsoluteTrajectoryError ComputeAte(const Trajectory& aligned_estimate,
                                   const Trajectory& ground_truth) {
  CheckSameSize(aligned_estimate, ground_truth, "ComputeAte");
  AbsoluteTrajectoryError ate;
  for (size_t i = 0; i < ground_truth.size(); ++i) {
    const StampedPose& P = aligned_estimate[i];
    const StampedPose& Q = ground_truth[i];
    ate.translation_m.push_back((Q.p_w_b - P.p_w_b).norm());
    // evo: E = P^-1 Q, error = angle of R(E) = R_P^T R_Q.
    ate.rotation_deg.push_back(AngleDeg(P.q_w_b.conjugate() * Q.q_w_b));
  }
  ate.translation = ComputeStats(ate.translation_m);
  ate.rotation = ComputeStats(ate.rotation_deg);
  return ate;
}

IndexPairs RpePairs(const Trajectory& estimate, double delta, RpeUnit unit) {
  if (!std::isfinite(delta) || delta <= 0.0) {
    throw std::invalid_argument("RPE delta must be > 0 (got " +
                                std::to_string(delta) + ")");
  }
  std::vector<size_t> marks;
  if (unit == RpeUnit::kFrames) {
    if (delta != std::floor(delta)) {
      throw std::invalid_argument(
          "RPE delta in frames must be a whole number (got " +
          std::to_string(delta) + ")");
    }
    const size_t step = static_cast<size_t>(delta);
    for (size_t i = 0; i < estimate.size(); i += step) marks.push_back(i);
  } else {
    double path = 0.0;  // [m] travelled since the last mark
    for (size_t i = 0; i < estimate.size(); ++i) {
      if (i > 0) path += (estimate[i].p_w_b - estimate[i - 1].p_w_b).norm();
      if (path >= delta) {
        marks.push_back(i);
        path = 0.0;
      }
    }
  }
  IndexPairs pairs;
  for (size_t k = 1; k < marks.size(); ++k) {
    pairs.emplace_back(marks[k - 1], marks[k]);
  }
  return pairs;
}

RelativePoseError ComputeRpe(const Trajectory& aligned_estimate,
                             const Trajectory& ground_truth, double delta,
                             RpeUnit unit) {
  CheckSameSize(aligned_estimate, ground_truth, "ComputeRpe");
  RelativePoseError rpe;
  rpe.delta = delta;
  rpe.unit = unit;
  rpe.pairs = RpePairs(aligned_estimate, delta, unit);
  for (const auto& [i, j] : rpe.pairs) {
    const StampedPose& P_i = aligned_estimate[i];
    const StampedPose& P_j = aligned_estimate[j];
    const StampedPose& Q_i = ground_truth[i];
    const StampedPose& Q_j = ground_truth[j];
    const Relative Q_rel = Between(Q_i.q_w_b, Q_i.p_w_b, Q_j.q_w_b, Q_j.p_w_b);
    const Relative P_rel = Between(P_i.q_w_b, P_i.p_w_b, P_j.q_w_b, P_j.p_w_b);
    const Relative E = Between(Q_rel.q, Q_rel.t, P_rel.q, P_rel.t);
    rpe.translation_m.push_back(E.t.norm());
    rpe.rotation_deg.push_back(AngleDeg(E.q));
  }
  rpe.translation = ComputeStats(rpe.translation_m);
  rpe.rotation = ComputeStats(rpe.rotation_deg);
  return rpe;
}

}  // namespace vio
