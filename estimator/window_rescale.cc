#include "estimator/window_rescale.h"

#include <utility>

namespace vio {
namespace {

enum class BlockRole { kOther, kPose, kSpeedBias, kPoint };

BlockRole RoleOf(const double* block, const Window& window,
                 const FeatureManager& features) {
  for (const auto& f : window.frames) {
    if (block == f->pose.data()) return BlockRole::kPose;
    if (block == f->speed_bias.data()) return BlockRole::kSpeedBias;
  }
  for (const auto& [id, l] : features.landmarks()) {
    if (l.world_point && block == l.p_w.data()) return BlockRole::kPoint;
  }
  return BlockRole::kOther;
}

void MapPoint(const WindowCorrection& k, double* p) {
  Eigen::Map<Eigen::Vector3d> x(p);
  x = k.c + k.s * (k.R * (x - k.c));
}

void MapVector(const WindowCorrection& k, double* v) {
  Eigen::Map<Eigen::Vector3d> x(v);
  x = k.s * (k.R * x);
}

void MapAttitude(const WindowCorrection& k, double* q) {
  Eigen::Map<Eigen::Quaterniond> x(q);
  x = (Eigen::Quaterniond(k.R) * x).normalized();
}

}  // namespace

void CorrectWindow(const WindowCorrection& k, Window* window,
                   FeatureManager* features) {
  for (auto& f : window->frames) {
    MapPoint(k, f->pose.data() + kPoseP);
    MapAttitude(k, f->pose.data() + kPoseQ);
    MapVector(k, f->speed_bias.data() + kSbV);
    f->b_a() += k.delta_b_a;
  }
  for (auto& [id, l] : features->landmarks()) {
    if (l.world_point) {
      MapPoint(k, l.p_w.data());
      MapPoint(k, l.p_w_first.data());
    } else {
      l.inverse_depth /= k.s;
    }
  }
}

std::unique_ptr<MarginalizationPrior> CorrectPrior(
    const MarginalizationPrior& prior, const std::vector<double*>& blocks,
    const WindowCorrection& k, const Window& window,
    const FeatureManager& features) {
  // On a mapped position or velocity x' = s R x + const, so that
  // x - x0 = R^T (x' - x0') / s: its columns J_x R^T / s. An attitude's
  // tangent Log(q0^-1 q) is unchanged by q -> R q (R q0)^-1 (R q) = q0^-1 q.
  const Eigen::Matrix3d M = k.R.transpose() / k.s;
  std::vector<PriorBlock> kept = prior.blocks();
  Eigen::MatrixXd J = prior.jacobian();
  for (size_t b = 0; b < kept.size() && b < blocks.size(); ++b) {
    const int col = prior.TangentOffset(static_cast<int>(b));
    std::vector<double>& x0 = kept[b].x0;
    switch (RoleOf(blocks[b], window, features)) {
      case BlockRole::kPose:  // tangent [dp, dtheta]
        MapPoint(k, x0.data() + kPoseP);
        MapAttitude(k, x0.data() + kPoseQ);
        J.middleCols(col + kPoseP, 3) = J.middleCols(col + kPoseP, 3) * M;
        break;
      case BlockRole::kSpeedBias:  // [v, b_a, b_g]; b_a shifted with x0
        MapVector(k, x0.data() + kSbV);
        for (int i = 0; i < 3; ++i) x0[kSbBa + i] += k.delta_b_a[i];
        J.middleCols(col + kSbV, 3) = J.middleCols(col + kSbV, 3) * M;
        break;
      case BlockRole::kPoint:
        MapPoint(k, x0.data());
        J.middleCols(col, 3) = J.middleCols(col, 3) * M;
        break;
      case BlockRole::kOther:
        break;
    }
  }
  return std::make_unique<MarginalizationPrior>(std::move(kept), std::move(J),
                                                prior.residual0());
}

}  // namespace vio
