#include "eval/epipolar_error.h"

#include <cmath>
#include <stdexcept>
#include <unordered_map>

namespace vio {
namespace {

constexpr double kMinBaselineM = 1e-3;

struct Frame {
  bool has_pose = false;
  Eigen::Isometry3d T_w_c = Eigen::Isometry3d::Identity();
  std::unordered_map<int64_t, Eigen::Vector3d> x;  // id -> (x, y, 1)
};

Eigen::Matrix3d Skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return m;
}

}  // namespace

EpipolarReport EvaluateEpipolarError(const std::vector<FeatureFrame>& frames,
                                     const CameraModel& camera,
                                     const Eigen::Isometry3d& T_b_c,
                                     const PoseAt& pose_at, int max_gap) {
  if (max_gap < 1) {
    throw std::invalid_argument("EvaluateEpipolarError: max_gap must be >= 1");
  }
  EpipolarReport report;
  std::vector<Frame> prepared(frames.size());
  for (size_t i = 0; i < frames.size(); ++i) {
    Eigen::Isometry3d T_w_b;
    if (!pose_at(frames[i].t_ns, &T_w_b)) {
      ++report.frames_without_pose;
      continue;
    }
    prepared[i].has_pose = true;
    prepared[i].T_w_c = T_w_b * T_b_c;
    for (const FeatureObservation& o : frames[i].observations) {
      Eigen::Vector2d xy;
      if (o.camera == 0 && camera.PixelToNormalized(o.uv, &xy)) {
        prepared[i].x[o.feature_id] = xy.homogeneous();
      }
    }
  }
  const double focal = camera.focal();
  for (int gap = 1; gap <= max_gap; ++gap) {
    std::vector<double> errors;
    for (size_t i = 0; i + gap < prepared.size(); ++i) {
      const Frame& a = prepared[i];
      const Frame& b = prepared[i + gap];
      if (!a.has_pose || !b.has_pose) continue;
      const Eigen::Isometry3d T_ba = b.T_w_c.inverse() * a.T_w_c;
      if (T_ba.translation().norm() < kMinBaselineM) {
        ++report.pairs_without_baseline;
        continue;
      }
      const Eigen::Matrix3d E = Skew(T_ba.translation()) * T_ba.linear();
      for (const auto& [id, x_a] : a.x) {
        const auto x_b = b.x.find(id);
        if (x_b == b.x.end()) continue;
        const Eigen::Vector3d l = E * x_a;
        errors.push_back(focal * std::abs(x_b->second.dot(l)) /
                         std::hypot(l.x(), l.y()));
      }
    }
    report.gaps.push_back({gap, ComputePixelErrorStats(errors)});
  }
  return report;
}

}  // namespace vio
