#ifndef VIO_FACTORS_CHECK_FACTOR_CASES_H_
#define VIO_FACTORS_CHECK_FACTOR_CASES_H_

// Every factor of the project, with a sampler of random realistic states.
// A factor is not done until it has a case here (used by tools/jacobian_check)
// and a numeric-differentiation test that draws from the same case.

#include <functional>
#include <string>
#include <vector>

#include "factors/check/jacobian_check.h"
#include "factors/check/visual_scene.h"

namespace vio {

// All cases, in a fixed order (the order of the jacobian_check table).
std::vector<FactorCase> AllFactorCases();

// The IMU factor (factors/imu_factor.h); check/imu_factor_case.cc.
FactorCase MakeImuFactorCase();
// A visual factor and how to build it at a scene of
// factors/check/visual_scene.h (for tests and benchmarks that need the same
// factor at chosen states).
struct VisualFactorKind {
  std::string name;  // as in jacobian_check --factor
  std::string description;
  VisualTarget target;  // which observation the factor's target is
  bool timed;           // whether the scene needs velocities and t_d
  std::function<FactorInstance(const VisualScene&)> make;
};
// reprojection, reprojection_td, stereo_same_frame, stereo_two_frame,
// stereo_two_frame_td.
const std::vector<VisualFactorKind>& VisualFactorKinds();

// The case of a visual factor on scenes of one geometry.
FactorCase MakeVisualCase(const VisualFactorKind& kind,
                          VisualGeometry geometry);

// Visual factors (visual_factor_cases.cc), on scenes from
// factors/check/visual_scene.h. With kMixed (what AllFactorCases uses) half
// the states are realistic and half sit close to a degenerate case (a point
// nearly at infinity, a negative inverse depth, a point centimetres in front
// of the target camera); a fixed geometry draws only that kind.
FactorCase MakeReprojectionCase(
    VisualGeometry geometry = VisualGeometry::kMixed);
FactorCase MakeTimedReprojectionCase(
    VisualGeometry geometry = VisualGeometry::kMixed);
FactorCase MakeStereoReprojectionCase(
    VisualGeometry geometry = VisualGeometry::kMixed);
FactorCase MakeStereoTwoFrameReprojectionCase(
    VisualGeometry geometry = VisualGeometry::kMixed);
FactorCase MakeTimedStereoTwoFrameReprojectionCase(
    VisualGeometry geometry = VisualGeometry::kMixed);

// The world-point reprojection factor (factors/world_point_factor.h) on the
// scenes above, the landmark at SceneWorldPoint (from the anchor's bearing at
// its pose's time); check/
// world_point_factor_case.cc. camera1: seen by camera 1 of keyframe j (the
// scene drawn with kStereoOtherFrame), else camera 0 (kMonoOtherFrame).
Eigen::Vector3d SceneWorldPoint(const VisualScene& scene);
FactorInstance MakeWorldPointReprojection(const VisualScene& scene,
                                          bool camera1);
FactorCase MakeWorldPointReprojectionCase();
// The same with a time offset (factors/timed_world_point_factor.h): the scene
// drawn timed, the factor on obs_j (its velocity and t_d_at_stamp) and the
// scene's t_d as a fourth block.
FactorInstance MakeTimedWorldPointReprojection(const VisualScene& scene,
                                               bool camera1);
FactorCase MakeTimedWorldPointReprojectionCase();

// The marginalisation prior (factors/marginalization_prior.h).
FactorCase MakeMarginalizationPriorCase();

// The photometric factor (factors/photometric_factor.h) on a synthetic
// smooth image; check/photometric_factor_case.cc.
FactorCase MakePhotometricCase();
// The zero-motion factor of a still vehicle (factors/zero_motion_factor.h).
FactorCase MakeZeroMotionFactorCase();

}  // namespace vio

#endif  // VIO_FACTORS_CHECK_FACTOR_CASES_H_
