#include "estimator/state_check.h"

#include <cmath>

namespace vio {
namespace {

template <size_t N>
bool AllFinite(const std::array<double, N>& values) {
  for (double v : values) {
    if (!std::isfinite(v)) return false;
  }
  return true;
}

bool UnitEnough(const std::array<double, 7>& pose) {
  const double norm = Eigen::Vector4d(pose.data() + kPoseQ).norm();
  return norm >= 0.5 && norm <= 2.0;
}

}  // namespace

const char* StateDefectName(StateDefect defect) {
  switch (defect) {
    case StateDefect::kNone:
      return "none";
    case StateDefect::kNonFinite:
      return "non-finite value";
    case StateDefect::kBadRotation:
      return "quaternion far from unit length";
    case StateDefect::kTooFast:
      return "speed beyond the limit";
  }
  return "unknown";
}

StateDefect CheckWindowState(const Window& window,
                             const FeatureManager& features,
                             double max_speed_m_s) {
  for (int c = 0; c < window.num_cameras; ++c) {
    if (!AllFinite(window.extrinsics[c])) return StateDefect::kNonFinite;
    if (!UnitEnough(window.extrinsics[c])) return StateDefect::kBadRotation;
  }
  if (!std::isfinite(window.t_d)) return StateDefect::kNonFinite;
  for (const auto& f : window.frames) {
    if (!AllFinite(f->pose) || !AllFinite(f->speed_bias)) {
      return StateDefect::kNonFinite;
    }
    if (!UnitEnough(f->pose)) return StateDefect::kBadRotation;
  }
  for (const auto& [id, l] : features.landmarks()) {
    if (l.triangulated && !std::isfinite(l.inverse_depth)) {
      return StateDefect::kNonFinite;
    }
  }
  for (const auto& f : window.frames) {
    if (f->v_w_value().norm() > max_speed_m_s) return StateDefect::kTooFast;
  }
  return StateDefect::kNone;
}

}  // namespace vio
