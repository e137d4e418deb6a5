#include "eval/pose_interpolation.h"

#include <algorithm>

namespace vio {

bool InterpolatePose(const Trajectory& trajectory, int64_t t_ns,
                     Eigen::Isometry3d* T_w_b) {
  if (trajectory.empty() || t_ns < trajectory.front().t_ns ||
      t_ns > trajectory.back().t_ns) {
    return false;
  }
  const auto after = std::lower_bound(
      trajectory.begin(), trajectory.end(), t_ns,
      [](const StampedPose& p, int64_t t) { return p.t_ns < t; });
  const StampedPose& b = *after;
  const StampedPose& a = after == trajectory.begin() ? b : *(after - 1);
  // Fraction from integer nanoseconds, so no precision is lost.
  const double s = b.t_ns == a.t_ns ? 0.0
                                    : static_cast<double>(t_ns - a.t_ns) /
                                          static_cast<double>(b.t_ns - a.t_ns);
  *T_w_b = Eigen::Isometry3d::Identity();
  T_w_b->translation() = (1.0 - s) * a.p_w_b + s * b.p_w_b;
  T_w_b->linear() =
      a.q_w_b.normalized().slerp(s, b.q_w_b.normalized()).toRotationMatrix();
  return true;
}

}  // namespace vio
