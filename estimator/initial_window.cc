#include "estimator/initial_window.h"

#include <cmath>

#include "estimator/static_initializer.h"

namespace vio {

void SetGauge(const Eigen::Vector3d& p_w_b, double yaw_rad,
              InitialWindow* window) {
  if (window->frames.empty()) return;
  const InitialFrame& newest = window->frames.back();
  // x' = Rz(dyaw) (x - p_newest) + p_w_b for every point and position;
  // q' = Rz(dyaw) q; v' = Rz(dyaw) v.
  const double dyaw =
      yaw_rad - Yaw(newest.q_w_b.normalized().toRotationMatrix());
  const Eigen::Quaterniond Rz(
      Eigen::AngleAxisd(dyaw, Eigen::Vector3d::UnitZ()));
  const Eigen::Vector3d origin = newest.p_w_b;
  for (InitialFrame& f : window->frames) {
    f.p_w_b = Rz * (f.p_w_b - origin) + p_w_b;
    f.q_w_b = (Rz * f.q_w_b).normalized();
    f.v_w = Rz * f.v_w;
  }
  for (auto& [id, p] : window->points_w) p = Rz * (p - origin) + p_w_b;
}

}  // namespace vio
