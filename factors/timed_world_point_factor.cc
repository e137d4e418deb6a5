#include "factors/timed_world_point_factor.h"

#include "factors/world_point_factor.h"

namespace vio {

TimedWorldPointReprojectionFactor::TimedWorldPointReprojectionFactor(
    const TimedObservation& obs, double sqrt_info, const double* p_w_first)
    : obs_(obs), sqrt_info_(sqrt_info), p_w_first_(p_w_first) {}

bool TimedWorldPointReprojectionFactor::Evaluate(
    double const* const* parameters, double* residuals,
    double** jacobians) const {
  return Compute(parameters, residuals, jacobians, /*tangent=*/false);
}

bool TimedWorldPointReprojectionFactor::EvaluateTangent(
    double const* const* parameters, double* residuals,
    double** jacobians) const {
  return Compute(parameters, residuals, jacobians, /*tangent=*/true);
}

bool TimedWorldPointReprojectionFactor::Compute(
    double const* const* parameters, double* residuals, double** jacobians,
    bool tangent) const {
  const double t_d = parameters[kTimeOffset][0];
  // xy_k(t_d) = xy_k - (t_d - t_d_k) v_k.
  const Eigen::Vector2d shifted =
      obs_.xy - (t_d - obs_.t_d_at_stamp) * obs_.velocity;
  // Pose, T_b_c and p_w (blocks 0..2, the plain factor's layout).
  const bool active = WorldPointReprojection(
      parameters, shifted, sqrt_info_, p_w_first_, tangent, residuals,
      jacobians);
  if (jacobians == nullptr || jacobians[kTimeOffset] == nullptr) return true;
  // d r / d t_d = sqrt_info v_k (header), zero when inactive.
  Eigen::Map<Eigen::Vector2d> d_r_d_td(jacobians[kTimeOffset]);
  if (active) {
    d_r_d_td = sqrt_info_ * obs_.velocity;
  } else {
    d_r_d_td.setZero();
  }
  return true;
}

}  // namespace vio
