// The world-point reprojection factors (factors/world_point_factor.h,
// factors/timed_world_point_factor.h) on the visual factors' scenes: the
// scene's landmark placed in the world, seen by camera 0 or camera 1 of
// keyframe j.

#include <memory>

#include "factors/check/factor_cases.h"
#include "factors/pose_manifold.h"
#include "factors/timed_world_point_factor.h"
#include "factors/world_point_factor.h"

namespace vio {

Eigen::Vector3d SceneWorldPoint(const VisualScene& s) {
  // The anchor's bearing at its pose's time (a timed scene stores it
  // shifted; an untimed one has no velocity).
  const Eigen::Vector2d xy_i =
      s.obs_i.xy - (s.t_d - s.obs_i.t_d_at_stamp) * s.obs_i.velocity;
  return IsometryFromBlock(s.pose_i) * IsometryFromBlock(s.extrinsic0) *
         (xy_i.homogeneous() / s.rho);
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

namespace {

// Half realistic, half centimetres in front of the target camera; camera 0
// or camera 1 (*camera1) of keyframe j. The draws in this order, as each
// case made them.
VisualScene SampleWorldPointScene(std::mt19937& rng, bool timed,
                                  bool* camera1) {
  const bool near = std::uniform_int_distribution<int>(0, 1)(rng) == 1;
  *camera1 = std::uniform_int_distribution<int>(0, 1)(rng) == 1;
  return SampleVisualScene(
      rng,
      near ? VisualGeometry::kNearTargetCamera : VisualGeometry::kRealistic,
      *camera1 ? VisualTarget::kStereoOtherFrame
               : VisualTarget::kMonoOtherFrame,
      timed, 1.5);
}

}  // namespace

FactorCase MakeWorldPointReprojectionCase() {
  FactorCase c;
  c.name = "world_point";
  c.description =
      "reprojection of a world point, cam0 or cam1 [pose, T_b_c, p_w]";
  c.sample = [](std::mt19937& rng) {
    bool camera1 = false;
    const VisualScene s = SampleWorldPointScene(rng, /*timed=*/false, &camera1);
    return MakeWorldPointReprojection(s, camera1);
  };
  return c;
}

FactorInstance MakeTimedWorldPointReprojection(const VisualScene& s,
                                               bool camera1) {
  FactorInstance f = MakeWorldPointReprojection(s, camera1);
  f.cost =
      std::make_unique<TimedWorldPointReprojectionFactor>(s.obs_j, s.sqrt_info);
  f.blocks.push_back({s.t_d});
  f.manifolds.push_back(nullptr);
  f.block_names.push_back("t_d");
  return f;
}

FactorCase MakeTimedWorldPointReprojectionCase() {
  FactorCase c;
  c.name = "world_point_td";
  c.description =
      "world_point with time offset, cam0 or cam1 [pose, T_b_c, p_w, t_d]";
  c.sample = [](std::mt19937& rng) {
    bool camera1 = false;
    const VisualScene s = SampleWorldPointScene(rng, /*timed=*/true, &camera1);
    return MakeTimedWorldPointReprojection(s, camera1);
  };
  return c;
}

}  // namespace vio
