#include <memory>

#include "factors/check/factor_cases.h"
#include "factors/pose_manifold.h"
#include "factors/reprojection_factor.h"
#include "factors/stereo_reprojection_factor.h"
#include "factors/timed_reprojection_factor.h"

namespace vio {
namespace {

std::vector<double> Values(const Block7& x) {
  return std::vector<double>(x.data(), x.data() + x.size());
}

// Appends a rigid (PoseManifold) or a scalar (Euclidean) block.
void AddRigid(const std::string& name, const Block7& x, FactorInstance* f) {
  static const auto kPose = std::make_shared<const PoseManifold>();
  f->blocks.push_back(Values(x));
  f->manifolds.push_back(kPose);
  f->block_names.push_back(name);
}

void AddScalar(const std::string& name, double x, FactorInstance* f) {
  f->blocks.push_back({x});
  f->manifolds.push_back(nullptr);
  f->block_names.push_back(name);
}

// 1.5 px of noise on the target observation keeps the residual non-zero.
constexpr double kNoisePx = 1.5;

FactorInstance MakeReprojection(const VisualScene& s) {
  FactorInstance f;
  f.cost =
      std::make_unique<ReprojectionFactor>(s.obs_i.xy, s.obs_j.xy, s.sqrt_info);
  AddRigid("pose_i", s.pose_i, &f);
  AddRigid("pose_j", s.pose_j, &f);
  AddRigid("T_b_c", s.extrinsic0, &f);
  AddScalar("rho", s.rho, &f);
  return f;
}

FactorInstance MakeTimedReprojection(const VisualScene& s) {
  FactorInstance f;
  f.cost =
      std::make_unique<TimedReprojectionFactor>(s.obs_i, s.obs_j, s.sqrt_info);
  AddRigid("pose_i", s.pose_i, &f);
  AddRigid("pose_j", s.pose_j, &f);
  AddRigid("T_b_c", s.extrinsic0, &f);
  AddScalar("rho", s.rho, &f);
  AddScalar("t_d", s.t_d, &f);
  return f;
}

FactorInstance MakeStereoSameFrame(const VisualScene& s) {
  FactorInstance f;
  f.cost = std::make_unique<StereoReprojectionFactor>(s.obs_i.xy, s.obs_j.xy,
                                                      s.sqrt_info);
  AddRigid("T_b_c0", s.extrinsic0, &f);
  AddRigid("T_b_c1", s.extrinsic1, &f);
  AddScalar("rho", s.rho, &f);
  return f;
}

FactorInstance MakeStereoTwoFrame(const VisualScene& s) {
  FactorInstance f;
  f.cost = std::make_unique<StereoTwoFrameReprojectionFactor>(
      s.obs_i.xy, s.obs_j.xy, s.sqrt_info);
  AddRigid("pose_i", s.pose_i, &f);
  AddRigid("pose_j", s.pose_j, &f);
  AddRigid("T_b_c0", s.extrinsic0, &f);
  AddRigid("T_b_c1", s.extrinsic1, &f);
  AddScalar("rho", s.rho, &f);
  return f;
}

FactorInstance MakeTimedStereoTwoFrame(const VisualScene& s) {
  FactorInstance f;
  f.cost = std::make_unique<TimedStereoTwoFrameReprojectionFactor>(
      s.obs_i, s.obs_j, s.sqrt_info);
  AddRigid("pose_i", s.pose_i, &f);
  AddRigid("pose_j", s.pose_j, &f);
  AddRigid("T_b_c0", s.extrinsic0, &f);
  AddRigid("T_b_c1", s.extrinsic1, &f);
  AddScalar("rho", s.rho, &f);
  AddScalar("t_d", s.t_d, &f);
  return f;
}

}  // namespace

FactorCase MakeVisualCase(const VisualFactorKind& kind,
                          VisualGeometry geometry) {
  FactorCase c;
  c.name = kind.name;
  c.description = kind.description;
  c.sample = [kind, geometry](std::mt19937& rng) {
    return kind.make(
        SampleVisualScene(rng, geometry, kind.target, kind.timed, kNoisePx));
  };
  return c;
}

const std::vector<VisualFactorKind>& VisualFactorKinds() {
  static const std::vector<VisualFactorKind> kKinds = {
      {"reprojection",
       "mono reprojection, inverse depth [pose_i, pose_j, T_b_c, rho]",
       VisualTarget::kMonoOtherFrame, false, MakeReprojection},
      {"reprojection_td",
       "mono reprojection with time offset [pose_i, pose_j, T_b_c, rho, t_d]",
       VisualTarget::kMonoOtherFrame, true, MakeTimedReprojection},
      {"stereo_same_frame",
       "cam0 anchor seen by cam1, same keyframe [T_b_c0, T_b_c1, rho]",
       VisualTarget::kStereoSameFrame, false, MakeStereoSameFrame},
      {"stereo_two_frame",
       "cam0 anchor seen by cam1 of another keyframe [pose_i, pose_j, "
       "T_b_c0, T_b_c1, rho]",
       VisualTarget::kStereoOtherFrame, false, MakeStereoTwoFrame},
      {"stereo_two_frame_td",
       "stereo_two_frame with time offset [pose_i, pose_j, T_b_c0, T_b_c1, "
       "rho, t_d]",
       VisualTarget::kStereoOtherFrame, true, MakeTimedStereoTwoFrame},
  };
  return kKinds;
}

FactorCase MakeReprojectionCase(VisualGeometry geometry) {
  return MakeVisualCase(VisualFactorKinds()[0], geometry);
}

FactorCase MakeTimedReprojectionCase(VisualGeometry geometry) {
  return MakeVisualCase(VisualFactorKinds()[1], geometry);
}

FactorCase MakeStereoReprojectionCase(VisualGeometry geometry) {
  return MakeVisualCase(VisualFactorKinds()[2], geometry);
}

FactorCase MakeStereoTwoFrameReprojectionCase(VisualGeometry geometry) {
  return MakeVisualCase(VisualFactorKinds()[3], geometry);
}

FactorCase MakeTimedStereoTwoFrameReprojectionCase(VisualGeometry geometry) {
  return MakeVisualCase(VisualFactorKinds()[4], geometry);
}

}  // namespace vio
