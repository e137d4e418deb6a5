#include "estimator/image_velocity.h"

#include <algorithm>

namespace vio {

Eigen::Vector2d PredictedImageVelocity(const Eigen::Vector3d& p_c,
                                       const Eigen::Isometry3d& T_w_b,
                                       const Eigen::Vector3d& v_w,
                                       const Eigen::Vector3d& w_b,
                                       const Eigen::Isometry3d& T_b_c) {
  // An inverse depth of 0 gives an infinite point: no velocity either.
  if (!p_c.allFinite() || !(p_c.z() > 0.0)) return Eigen::Vector2d::Zero();
  // p_c = R_c_w (p_w - p_w_c); with d R_w_c / dt = R_w_c [w_c]x,
  // d R_c_w / dt = -[w_c]x R_c_w, hence d p_c / dt = -w_c x p_c - R_c_w v_w_c.
  const Eigen::Matrix3d R_c_b = T_b_c.linear().transpose();
  const Eigen::Matrix3d R_c_w = R_c_b * T_w_b.linear().transpose();
  const Eigen::Vector3d w_c = R_c_b * w_b;
  const Eigen::Vector3d v_w_c =
      v_w + T_w_b.linear() * w_b.cross(T_b_c.translation());
  const Eigen::Vector3d dp_c = -w_c.cross(p_c) - R_c_w * v_w_c;
  // Quotient rule on xy = p_c.xy / p_c.z.
  const Eigen::Vector2d xy = p_c.head<2>() / p_c.z();
  return (dp_c.head<2>() - xy * dp_c.z()) / p_c.z();
}

Eigen::Vector3d GyroscopeAt(const std::vector<ImuSample>& imu, int64_t t_ns) {
  if (imu.empty()) return Eigen::Vector3d::Zero();
  const auto after = std::lower_bound(
      imu.begin(), imu.end(), t_ns,
      [](const ImuSample& s, int64_t t) { return s.t_ns < t; });
  if (after == imu.end()) return imu.back().gyr;
  if (after == imu.begin() || after->t_ns == t_ns) return after->gyr;
  const ImuSample& before = *(after - 1);
  const double u = static_cast<double>(t_ns - before.t_ns) /
                   static_cast<double>(after->t_ns - before.t_ns);
  return (1.0 - u) * before.gyr + u * after->gyr;
}

}  // namespace vio
