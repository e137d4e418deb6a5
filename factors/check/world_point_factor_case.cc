// The world-point reprojection factor (factors/world_point_factor.h) on the
// visual factors' scenes: the scene's landmark placed in the world, seen by
// camera 0 or camera 1 of keyframe j.

#include <memory>

#include "factors/check/factor_cases.h"
#include "factors/pose_manifold.h"
#include "factors/world_point_factor.h"

namespace vio {

Eigen::Vector3d SceneWorldPoint(const VisualScene& s) {
  return IsometryFromBlock(s.pose_i) * IsometryFromBlock(s.extrinsic0) *
         (s.obs_i.xy.homogeneous() / s.rho);
}

FactorInstance MakeWorldPointReprojection(const VisualScene& s, bool camera1) {
  static const auto kPose = std::make_shared<const PoseManifold>();
  FactorInstance f;
  f.cost =
      std::make_unique<WorldPointReprojectionFactor>(s.obs_j.xy, s.sqrt_info);
  const Block7& extrinsic = camera1 ? s.extrinsic1 : s.extrinsic0;
  const Eigen::Vector3d p_w = SceneWorldPoint(s);
  f.blocks = {std::vector<double>(s.pose_j.data(), s.pose_j.data() + 7),
              std::vector<double>(extrinsic.data(), extrinsic.data() + 7),
              std::vector<double>(p_w.data(), p_w.data() + 3)};
  f.manifolds = {kPose, kPose, nullptr};
  f.block_names = {"pose", camera1 ? "T_b_c1" : "T_b_c0", "p_w"};
  return f;
}

FactorCase MakeWorldPointReprojectionCase() {
  FactorCase c;
  c.name = "world_point";
  c.description =
      "reprojection of a world point, cam0 or cam1 [pose, T_b_c, p_w]";
  c.sample = [](std::mt19937& rng) {
    // Half realistic, half centimetres in front of the target camera;
    // camera 0 or camera 1 of keyframe j.
    const bool near = std::uniform_int_distribution<int>(0, 1)(rng) == 1;
    const bool camera1 = std::uniform_int_distribution<int>(0, 1)(rng) == 1;
    const VisualScene s = SampleVisualScene(
        rng,
        near ? VisualGeometry::kNearTargetCamera : VisualGeometry::kRealistic,
        camera1 ? VisualTarget::kStereoOtherFrame
                : VisualTarget::kMonoOtherFrame,
        /*timed=*/false, 1.5);
    return MakeWorldPointReprojection(s, camera1);
  };
  return c;
}

}  // namespace vio
