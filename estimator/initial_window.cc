#include "estimator/initial_window.h"

#include <cmath>

#include "estimator/static_initializer.h"

namespace vio {

namespace {

// x' = Rz(dyaw) (x - p_newest) + p_w_b for every point and position;
// q' = Rz(dyaw) q; v' = Rz(dyaw) v.
void MoveAboutZ(const Eigen::Vector3d& p_w_b, double dyaw,
                InitialWindow* window) {
  const Eigen::Quaterniond Rz(
      Eigen::AngleAxisd(dyaw, Eigen::Vector3d::UnitZ()));
  const Eigen::Vector3d origin = window->frames.back().p_w_b;
  for (InitialFrame& f : window->frames) {
    f.p_w_b = Rz * (f.p_w_b - origin) + p_w_b;
    f.q_w_b = (Rz * f.q_w_b).normalized();
    f.v_w = Rz * f.v_w;
  }
  for (auto& [id, p] : window->points_w) p = Rz * (p - origin) + p_w_b;
}

}  // namespace

void SetGauge(const Eigen::Vector3d& p_w_b, double yaw_rad,
              InitialWindow* window) {
  if (window->frames.empty()) return;
  const Eigen::Quaterniond q = window->frames.back().q_w_b.normalized();
  MoveAboutZ(p_w_b, yaw_rad - Yaw(q.toRotationMatrix()), window);
}

void SetGauge(const Eigen::Vector3d& p_w_b, const Eigen::Quaterniond& q_w_b,
              InitialWindow* window) {
  if (window->frames.empty()) return;
  const Eigen::Quaterniond q = window->frames.back().q_w_b.normalized();
  MoveAboutZ(
      p_w_b,
      YawBetween(q.toRotationMatrix(), q_w_b.normalized().toRotationMatrix()),
      window);
}

bool ScaleChangeDefined(const InitDiagnostics& diagnostics) {
  return diagnostics.refined_path_m >= kMinScalePathM &&
         diagnostics.refined_scale_sigma >= 0.0 &&
         diagnostics.refined_scale_sigma <= kMaxDefinedScaleSigma;
}

double YawBetween(const Eigen::Matrix3d& R_from, const Eigen::Matrix3d& R_to) {
  // |Rz A - B|_F^2 = 6 - 2 tr(B^T Rz A) = 6 - 2 tr(Rz N), N = A B^T, and
  // tr(Rz N) = cos(theta) (N00 + N11) + sin(theta) (N01 - N10) + N22,
  // largest at theta = atan2(N01 - N10, N00 + N11).
  const Eigen::Matrix3d N = R_from * R_to.transpose();
  return std::atan2(N(0, 1) - N(1, 0), N(0, 0) + N(1, 1));
}

}  // namespace vio
